"""The Python package tetray against analytic images: the plane z = 0.25 of the field f = z on a
tet box, seen head-on, on any number of ranks (each rank holds every point and a share of the
tets). Also the argument and status errors, after which the adaptor still renders, the trigger,
report and context manager, and that other threads run during execute."""

import pathlib
import shutil
import tempfile
import threading
import time
import unittest
import warnings

import numpy as np
from mpi4py import MPI

import support
import tetray

WIDTH, HEIGHT, EYE_Z, FOV_DEG, ISO = 64, 48, 5.0, 40.0, 0.25
COMM = MPI.COMM_WORLD


def config(directory, trigger="", width=WIDTH, height=HEIGHT, output_keys=""):
    return (f"output: {{directory: {directory}, quiet: true, formats: [png], "
            f"writer_queue_depth: 0{output_keys}}}\n{trigger}"
            "scenes:\n"
            "  - name: plane\n"
            "    field: f\n"
            f"    isovalues: [{ISO}]\n"
            f"    camera: {{eye: [0, 0, {EYE_Z}], look_at: [0, 0, 0], up: [0, 1, 0], "
            f"fov_deg: {FOV_DEG}}}\n"
            f"    image: {{width: {width}, height: {height}}}\n")


class Scene:
    """The box mesh with f = z; this rank's share of the tets (every rank has every point)."""

    def __init__(self, cells=4):
        self.points, all_tets = support.box_mesh(cells)
        self.tets = all_tets[COMM.rank::COMM.size].copy()
        self.global_ids = np.arange(len(all_tets), dtype=np.int64)[COMM.rank::COMM.size].copy()
        self.fields = {"f": self.points[:, 2].copy()}

    def centroids(self):
        return self.points[self.tets].mean(axis=1)


class AdaptorCase(unittest.TestCase):
    """A scene, a private directory and the checks of its image; no tests of its own."""

    @classmethod
    def setUpClass(cls):
        root = tempfile.mkdtemp(prefix="tetray_python_") if COMM.rank == 0 else None
        cls.root = pathlib.Path(COMM.bcast(root))
        cls.scene = Scene()

    @classmethod
    def tearDownClass(cls):
        COMM.Barrier()
        if COMM.rank == 0:
            shutil.rmtree(cls.root)

    def directory(self):
        return self.root / self.id().rsplit(".", 1)[-1]

    def adaptor(self, trigger=""):
        return tetray.Adaptor.from_yaml(COMM, config(self.directory(), trigger))

    def image(self, step=0):
        """The written image of `step` on the writer rank (rank 0), None on the others."""
        if COMM.rank != 0:
            return None
        return support.read_png(self.directory() / "plane" / f"plane_{step:06d}.png")

    def render(self, **arrays):
        """Renders step 0 with the scene's arrays, overridden by `arrays`; returns the report and
        the image (None off the writer rank)."""
        s = self.scene
        views = dict(points=s.points, tets=s.tets, fields=s.fields) | arrays
        with self.adaptor() as a:
            report = a.execute(0, 0.0, **views)
        return report, self.image()

    def assert_square(self, image, plane_z=ISO, keep=None):
        """The pixels that see surface are those whose ray meets the square at z = plane_z,
        up to the pixels at its edge (and, with `keep`, where keep(x) of the hit point holds)."""
        if image is None:
            return
        sure, possible, x = support.square_coverage(WIDTH, HEIGHT, EYE_Z, plane_z, FOV_DEG)
        if keep is not None:
            sure, possible = sure & keep(x, -1e-3), possible & keep(x, 1e-3)
        hit = image[:, :, 3] > 0
        self.assertGreater(sure.sum(), 100)
        self.assertEqual(int((sure & ~hit).sum()), 0, "pixels that must see the surface")
        self.assertEqual(int((hit & ~possible).sum()), 0, "pixels that must see background")


class AdaptorTest(AdaptorCase):
    def test_plane_where_the_camera_sees_it(self):
        report, image = self.render()
        self.assert_square(image)
        self.assertTrue(report.rendered)
        self.assertEqual(report.scenes_rendered, 1)
        self.assertEqual(report.bvh_decision, "rebuild")
        self.assertEqual(report.tets_skipped, 0)
        self.assertGreater(report.seconds_blocked, 0)

    def test_float32_points_and_int32_tets_give_the_same_image(self):
        _, wide = self.render()
        s = self.scene
        _, narrow = self.render(points=s.points.astype(np.float32), tets=s.tets.astype(np.int32),
                                fields={"f": s.fields["f"].astype(np.float32)})
        if COMM.rank == 0:
            np.testing.assert_array_equal(wide, narrow)

    def test_global_ids_give_the_same_image(self):
        _, without = self.render()
        _, with_ids = self.render(global_ids=self.scene.global_ids)
        if COMM.rank == 0:
            np.testing.assert_array_equal(without, with_ids)

    def test_displacement_moves_the_surface(self):
        lift = np.zeros_like(self.scene.points)
        lift[:, 2] = 0.75
        _, image = self.render(displacement=lift)
        self.assert_square(image, plane_z=ISO + 0.75)

    def test_ghost_tets_are_not_drawn(self):
        for flag in (1, 32):  # vtkGhostType DUPLICATECELL, HIDDENCELL
            ghost = np.where(self.scene.centroids()[:, 0] > 0, flag, 0).astype(np.uint8)
            _, image = self.render(ghost=ghost)
            self.assert_square(image, keep=lambda x, slack: x < slack)

    def test_other_threads_run_during_execute(self):
        """execute releases the GIL: a thread that keeps stamping the time gets to run while the
        step renders and (on the writer rank) encodes a large PNG inside the call."""
        s = self.scene
        stamps, stop = [], threading.Event()

        def stamp():
            while not stop.is_set():
                stamps.append(time.perf_counter())
                time.sleep(0.001)

        big = config(self.directory(), width=512, height=512, output_keys=", png_compression: 9")
        with tetray.Adaptor.from_yaml(COMM, big) as a:
            ticker = threading.Thread(target=stamp)
            ticker.start()
            start = time.perf_counter()
            a.execute(0, 0.0, s.points, s.tets, s.fields)
            end = time.perf_counter()
            stop.set()
            ticker.join()
        if COMM.rank == 0:  # the other ranks' part of the step may be too short to see
            margin = 0.1 * (end - start)
            inside = [t for t in stamps if start + margin < t < end - margin]
            self.assertGreater(len(inside), 0, f"no stamp during {end - start:.3f} s of execute")

    def test_will_render_follows_the_trigger(self):
        s = self.scene
        with self.adaptor(trigger="trigger: {every: 3}\n") as a:
            self.assertEqual([a.will_render(step, 0.1 * step) for step in range(5)],
                             [True, False, False, True, False])
            for step in range(4):
                report = a.execute(step, 0.1 * step, s.points, s.tets, s.fields)
                self.assertEqual(report.rendered, step in (0, 3))
                self.assertEqual(report.scenes_rendered, 1 if step in (0, 3) else 0)
        if COMM.rank == 0:
            written = sorted(p.name for p in (self.directory() / "plane").glob("*.png"))
            self.assertEqual(written, ["plane_000000.png", "plane_000003.png"])
        self.assert_square(self.image(3))

    def test_changes_refit_instead_of_rebuild(self):
        s = self.scene
        with self.adaptor() as a:
            a.execute(0, 0.0, s.points, s.tets, s.fields)
            moved = a.execute(1, 0.1, s.points, s.tets, s.fields,
                              changes=tetray.Changes(topology=False, fields=False))
            values = a.execute(2, 0.2, s.points, s.tets, s.fields,
                               changes=tetray.Changes(geometry=False, topology=False))
        self.assertEqual(moved.bvh_decision, "refit")
        self.assertEqual(values.bvh_decision, "field_refit")

    def test_hexahedra_as_cells_show_the_plane(self):
        """The box's cubes as hexahedra (split by the adaptor) show the plane f = z = ISO exactly
        (f is linear), on any rank count; ghost flags are per cell."""
        types, offsets, connectivity = support.box_hexahedra(4)
        mine = np.arange(COMM.rank, len(types), COMM.size)
        starts = offsets[mine]
        share = (types[mine].copy(), np.arange(0, 8 * len(mine) + 1, 8, dtype=np.int64),
                 np.concatenate([connectivity[s:s + 8] for s in starts]).astype(np.int64))
        _, image = self.render(tets=None, cells=share)
        self.assert_square(image)
        narrow = tuple(a.astype(np.int32) if a.dtype == np.int64 else a for a in share)
        _, narrow_image = self.render(tets=None, cells=narrow)
        if COMM.rank == 0:
            np.testing.assert_array_equal(image, narrow_image)
        cube_x = self.scene.points[share[2].reshape(-1, 8)].mean(axis=1)[:, 0]
        _, ghosted = self.render(tets=None, cells=share, ghost=(cube_x > 0).astype(np.uint8))
        self.assert_square(ghosted, keep=lambda x, slack: x < slack)

    def test_bad_cells_raise_and_name_the_problem(self):
        s = self.scene
        types, offsets, connectivity = support.box_hexahedra(4)
        bad_type = types.copy()
        bad_type[3] = 42
        cases = [
            (TypeError, "cells: expected a tuple", dict(cells=[types, offsets, connectivity])),
            (TypeError, "cells types", dict(cells=(types.astype(np.int32), offsets,
                                                   connectivity))),
            (TypeError, "same dtype", dict(cells=(types, offsets, connectivity.astype(np.int32)))),
            (ValueError, "cells offsets", dict(cells=(types, offsets[:-1].copy(), connectivity))),
            (ValueError, "offsets[-1]", dict(cells=(types, offsets, connectivity[:-1].copy()))),
            (ValueError, "either tets or cells", dict(cells=(types, offsets, connectivity),
                                                      tets=s.tets)),
            (ValueError, "either tets or cells", dict(tets=None)),
            (ValueError, "global_ids", dict(cells=(types, offsets, connectivity), tets=None,
                                            global_ids=s.global_ids)),
            (tetray.Error, "cell 3 (VTK cell type 42)", dict(cells=(bad_type, offsets,
                                                                    connectivity), tets=None)),
        ]
        with self.adaptor() as a:
            for error, message, bad in cases:
                views = dict(points=s.points, tets=None, fields=s.fields) | bad
                with self.subTest(bad=message), self.assertRaises(error) as raised:
                    a.execute(0, 0.0, **views)
                self.assertIn(message, str(raised.exception))
            self.assertTrue(a.execute(0, 0.0, s.points, s.tets, s.fields).rendered)
        self.assert_square(self.image())

    def test_bad_arguments_raise_and_the_next_call_renders(self):
        s = self.scene
        n, m = len(s.points), len(s.tets)
        big_endian = s.points.astype(">f8")
        cases = [
            (TypeError, "points", dict(points=s.points.tolist())),
            (TypeError, "points", dict(points=s.points.astype(np.int64))),
            (TypeError, "points", dict(points=big_endian)),
            (ValueError, "points", dict(points=s.points[:, :2].copy())),
            (ValueError, "C-contiguous", dict(points=np.asfortranarray(s.points))),
            (ValueError, "C-contiguous", dict(points=np.repeat(s.points, 2, axis=0)[::2])),
            (TypeError, "tets", dict(tets=s.tets.astype(np.float64))),
            (ValueError, "tets", dict(tets=s.tets[:, :3].copy())),
            (TypeError, "fields", dict(fields=[s.fields["f"]])),
            (TypeError, "fields", dict(fields={1: s.fields["f"]})),
            (TypeError, "fields['f']", dict(fields={"f": s.fields["f"].astype(np.int32)})),
            (ValueError, "fields['f']", dict(fields={"f": s.fields["f"].reshape(-1, 1)})),
            (ValueError, "displacement", dict(displacement=np.zeros((n - 1, 3)))),
            (TypeError, "ghost", dict(ghost=np.zeros(m, dtype=bool))),
            (ValueError, "ghost", dict(ghost=np.zeros(m + 1, dtype=np.uint8))),
            (TypeError, "global_ids", dict(global_ids=s.global_ids.astype(np.int32))),
        ]
        with self.adaptor() as a:
            for error, name, bad in cases:
                views = dict(points=s.points, tets=s.tets, fields=s.fields) | bad
                with self.subTest(bad=list(bad)), self.assertRaises(error) as raised:
                    a.execute(0, 0.0, **views)
                self.assertIn(name, str(raised.exception))
            self.assertTrue(a.execute(0, 0.0, s.points, s.tets, s.fields).rendered)
        self.assert_square(self.image())

    def test_failed_statuses_raise_tetray_error_and_the_next_call_renders(self):
        s = self.scene
        out_of_range = s.tets.copy()
        out_of_range[0, 0] = len(s.points)
        nan = s.fields["f"].copy()
        nan[0] = np.nan
        cases = [dict(tets=out_of_range), dict(fields={"f": s.fields["f"][:-1].copy()})]
        with self.adaptor() as a:
            for bad in cases:
                views = dict(points=s.points, tets=s.tets, fields=s.fields) | bad
                with self.subTest(bad=list(bad)), self.assertRaises(tetray.Error) as raised:
                    a.execute(0, 0.0, **views)
                error = raised.exception
                self.assertIsInstance(error, RuntimeError)
                self.assertEqual(error.code, tetray.StatusCode.invalid_argument)
                self.assertEqual(error.code.name, "invalid_argument")
                self.assertEqual(int(error.code), 1)
                self.assertTrue(error.message)
                self.assertIn(error.message, str(error))
            self.assertTrue(a.execute(0, 0.0, s.points, s.tets, s.fields).rendered)
        self.assert_square(self.image())

    def test_a_scene_whose_field_is_unusable_is_skipped_with_a_warning(self):
        s = self.scene
        nan = s.fields["f"].copy()
        nan[0] = np.nan
        with self.adaptor() as a:
            for fields in ({"g": s.fields["f"]}, {"f": nan}):
                with self.subTest(fields=list(fields)), self.assertWarns(
                        tetray.PartialWarning) as warned:
                    report = a.execute(0, 0.0, s.points, s.tets, fields)
                self.assertEqual(report.skipped_scenes, ["plane"])
                self.assertEqual(report.scenes_rendered, 0)
                self.assertIn("plane", str(warned.warning))
            with warnings.catch_warnings():
                warnings.simplefilter("error", tetray.PartialWarning)
                with self.assertRaises(tetray.PartialWarning):
                    a.execute(0, 0.0, s.points, s.tets, {"g": s.fields["f"]})
            report = a.execute(0, 0.0, s.points, s.tets, s.fields)
            self.assertTrue(report.rendered)
            self.assertEqual(report.skipped_scenes, [])
        self.assert_square(self.image())

    def test_config_errors_raise_tetray_error(self):
        with self.assertRaises(tetray.Error) as raised:
            tetray.Adaptor.from_yaml(COMM, config(self.directory()) + "colour: red\n")
        self.assertEqual(raised.exception.code, tetray.StatusCode.config_error)
        self.assertIn("colour", raised.exception.message)
        with self.assertRaises(tetray.Error) as raised:
            tetray.Adaptor(COMM, self.directory() / "missing.yaml")
        self.assertEqual(raised.exception.code, tetray.StatusCode.config_error)
        self.assertIn("missing.yaml", raised.exception.message)

    def test_config_file_as_path(self):
        path = self.root / "plane.yaml"
        if COMM.rank == 0:
            path.write_text(config(self.directory()))
        COMM.Barrier()
        s = self.scene
        with tetray.Adaptor(COMM, path) as a:
            a.execute(0, 0.0, s.points, s.tets, s.fields)
        self.assert_square(self.image())

    def test_comm_must_be_an_mpi4py_communicator(self):
        with self.assertRaises(TypeError) as raised:
            tetray.Adaptor.from_yaml("world", config(self.directory()))
        self.assertIn("comm", str(raised.exception))

    def test_with_block_finalizes(self):
        s = self.scene
        with self.adaptor() as a:
            a.execute(0, 0.0, s.points, s.tets, s.fields)
        with self.assertRaises(tetray.Error) as raised:
            a.execute(1, 0.1, s.points, s.tets, s.fields)
        self.assertEqual(raised.exception.code, tetray.StatusCode.not_initialized)
        a.finalize()
        self.assert_square(self.image())


class AcrossRanksTest(AdaptorCase):
    """Only on two ranks or more: ctest runs it under mpirun, and the one-rank run names
    AdaptorTest alone. On one rank it fails rather than pass without testing."""

    def setUp(self):
        self.assertGreaterEqual(COMM.size, 2, "AcrossRanksTest needs mpirun -n 2 or more")

    def test_one_rank_with_a_bad_argument_does_not_stop_the_others(self):
        s = self.scene
        with self.adaptor() as a:
            if COMM.rank == 1:
                with self.assertRaises(TypeError):
                    a.execute(0, 0.0, s.points, s.tets.astype(np.float32), s.fields)
            else:
                with self.assertRaises(tetray.Error) as raised:
                    a.execute(0, 0.0, s.points, s.tets, s.fields)
                self.assertIn("rank 1", raised.exception.message)
            self.assertTrue(a.execute(0, 0.0, s.points, s.tets, s.fields).rendered)
        self.assert_square(self.image())

    def test_ranks_without_tets_pass_empty_arrays(self):
        s = self.scene
        _, all_tets = support.box_mesh(4)
        if COMM.rank == 0:
            views = dict(points=s.points, tets=all_tets, fields=s.fields)
        else:
            views = dict(points=np.empty((0, 3)), tets=np.empty((0, 4), dtype=np.int64))
        with self.adaptor() as a:
            self.assertTrue(a.execute(0, 0.0, **views).rendered)
        self.assert_square(self.image())


if __name__ == "__main__":
    support.run_on_every_rank()

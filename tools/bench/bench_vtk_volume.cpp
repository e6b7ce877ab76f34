#include "bench_vtk_volume.hpp"

#include <X11/Xlib.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkProjectedTetrahedraMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGridLinearRayIntegrator.h>
#include <vtkUnstructuredGridPartialPreIntegration.h>
#include <vtkUnstructuredGridVolumeMapper.h>
#include <vtkUnstructuredGridVolumeRayCastMapper.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <cstdio>
#include <cstdlib>
#include <functional>

#include "bench_reference_vtk.hpp"
#include "bench_timing.hpp"
#include "bench_walk.hpp"
#include "render/walk/volume_render.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {
namespace {

// VTK's X window aborts the process without a display, so ask X first.
std::string display_problem() {
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) {
    const char* name = std::getenv("DISPLAY");
    return std::string("no X display could be opened (DISPLAY=") + (name ? name : "unset") +
           "); run under xvfb-run -a to measure VTK's volume rendering";
  }
  XCloseDisplay(display);
  return "";
}

void set_transfer_function(vtkVolumeProperty& property, const render::TransferFunction& tf) {
  vtkNew<vtkColorTransferFunction> color;
  color->SetColorSpaceToRGB();
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const double value : tf.breakpoints()) {
    const render::TransferFunction::Sample s = tf.at(value);
    color->AddRGBPoint(value, s.color[0], s.color[1], s.color[2]);
    opacity->AddPoint(value, s.extinction * tf.unit_distance);
  }
  property.SetColor(color);
  property.SetScalarOpacity(opacity);
  property.SetScalarOpacityUnitDistance(tf.unit_distance);
  property.SetInterpolationTypeToLinear();
  property.ShadeOff();
}

void set_camera(vtkRenderer& renderer, const render::Camera& camera) {
  vtkCamera* vtk_camera = renderer.GetActiveCamera();
  vtk_camera->SetPosition(camera.eye.x, camera.eye.y, camera.eye.z);
  vtk_camera->SetFocalPoint(camera.look_at.x, camera.look_at.y, camera.look_at.z);
  vtk_camera->SetViewUp(camera.up.x, camera.up.y, camera.up.z);
  vtk_camera->SetViewAngle(camera.fov_deg);  // vertical, as tetray's
  renderer.ResetCameraClippingRange();
}

// The window's pixels as a linear RGBA image, top row first as tetray's.
render::Framebuffer read_back(vtkRenderWindow& window, int width, int height) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(&window);
  grab->SetInputBufferTypeToRGBA();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  render::Framebuffer image(width, height);
  if (bytes == nullptr) return image;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const vtkIdType from = static_cast<vtkIdType>(height - 1 - j) * width + i;
      for (int c = 0; c < 4; ++c) {
        image.rgba[4 * image.index(i, j) + c] =
            static_cast<float>(bytes->GetValue(4 * from + c)) / 255.0f;
      }
    }
  }
  return image;
}

struct PeerMapper {
  const char* name;
  std::function<vtkSmartPointer<vtkUnstructuredGridVolumeMapper>(int threads)> make;
};

// The ray caster at full resolution: no sample-distance adjustment for interactive rates.
vtkSmartPointer<vtkUnstructuredGridVolumeMapper> ray_caster(
    vtkUnstructuredGridVolumeRayIntegrator* how, int threads) {
  auto mapper = vtkSmartPointer<vtkUnstructuredGridVolumeRayCastMapper>::New();
  mapper->SetRayIntegrator(how);
  mapper->SetNumberOfThreads(threads);
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetImageSampleDistance(1.0);
  return mapper;
}

const PeerMapper kMappers[] = {
    {"ray cast, linear integrator",
     [](int threads) {
       return ray_caster(vtkNew<vtkUnstructuredGridLinearRayIntegrator>(), threads);
     }},
    {"ray cast, partial pre-integration",
     [](int threads) {
       return ray_caster(vtkNew<vtkUnstructuredGridPartialPreIntegration>(), threads);
     }},
    {"projected tetrahedra (OpenGL)",
     [](int) -> vtkSmartPointer<vtkUnstructuredGridVolumeMapper> {
       return vtkSmartPointer<vtkProjectedTetrahedraMapper>::New();
     }},
};

render::Framebuffer tetray_frame(const GyroidTwist& scene, const render::Camera& camera,
                                 double& ms) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  const render::WalkStructure walk = render::build_walk_structure(volume);
  render::VolumeFragmentImage fragments;
  render::VolumeRenderOptions options = dvr_options(1.0);
  options.bvh = &bvh;  // as in situ: empty-space skipping on (nothing is empty here)
  ms = best_ms(kRepetitions,
               [&] { fragments = render::render_volume(volume, walk, camera, options); });
  return render::resolve(fragments);
}

}  // namespace

VtkVolumeFigures measure_vtk_volume(const GyroidTwist& scene, const render::Camera& camera,
                                    int threads) {
  VtkVolumeFigures figures;
  figures.skipped = display_problem();
  if (!figures.skipped.empty()) return figures;
  const render::Framebuffer tetray_image = tetray_frame(scene, camera, figures.tetray_ms);
  const vtkSmartPointer<vtkUnstructuredGrid> grid = make_grid(scene.mesh.tets);
  set_grid_step(*grid, scene.mesh.points, scene.field);
  vtkNew<vtkVolumeProperty> property;
  set_transfer_function(*property, dvr_options(1.0).transfer);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->SetBackgroundAlpha(0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetAlphaBitPlanes(1);
  window->SetSize(camera.width, camera.height);
  window->AddRenderer(renderer);
  for (const PeerMapper& peer : kMappers) {
    const vtkSmartPointer<vtkUnstructuredGridVolumeMapper> mapper = peer.make(threads);
    mapper->SetInputData(grid);
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(property);
    renderer->AddVolume(volume);
    set_camera(*renderer, camera);
    VtkVolumeRun run;
    run.mapper = peer.name;
    run.first_ms = time_ms([&] { window->Render(); });
    run.render_ms = best_ms(
        kRepetitions, [&] { renderer->GetActiveCamera()->Modified(); }, [&] { window->Render(); });
    run.difference =
        image_error(tetray_image, read_back(*window, camera.width, camera.height), camera, 3);
    figures.runs.push_back(run);
    renderer->RemoveVolume(volume);
  }
  return figures;
}

void print_vtk_volume(const VtkVolumeFigures& f) {
  if (!f.skipped.empty()) {
    std::printf("  VTK volume rendering: skipped: %s\n", f.skipped.c_str());
    return;
  }
  std::printf("  VTK volume rendering (tetray without early termination: %.1f ms):\n", f.tetray_ms);
  std::printf("    %-36s %10s %10s %12s %12s\n", "mapper", "first ms", "ms", "mean |dRGB|",
              "max |dRGB|");
  for (const VtkVolumeRun& r : f.runs) {
    std::printf("    %-36s %10.1f %10.1f %12.2e %12.2e\n", r.mapper.c_str(), r.first_ms,
                r.render_ms, r.difference.color_mean, r.difference.color_max);
  }
}

Json::Value vtk_volume_json(const VtkVolumeFigures& f) {
  Json::Value json;
  if (!f.skipped.empty()) {
    json["skipped"] = f.skipped;
    return json;
  }
  json["tetray_no_termination_ms"] = f.tetray_ms;
  json["runs"] = Json::Value(Json::arrayValue);
  for (const VtkVolumeRun& r : f.runs) {
    Json::Value run;
    run["mapper"] = r.mapper;
    run["first_ms"] = r.first_ms;
    run["render_ms"] = r.render_ms;
    run["mean_rgb_difference"] = r.difference.color_mean;
    run["max_rgb_difference"] = r.difference.color_max;
    json["runs"].append(run);
  }
  return json;
}

}  // namespace tetray::bench

#!/usr/bin/python3
"""The compositor under SimGrid's SMPI against real processes (docs/scaling.md).

Builds the simulator's configuration (-DTETRAY_SMPI=ON, smpicxx) from SOURCE into BUILD, then at
RANKS ranks, every algorithm, both row orders, dense and sparse images of two sizes (one odd):
- the simulator on real images and real mpirun composite the same image on the root (the hash
  of its every pixel), so the simulator runs the real code;
- the simulator's model images (where the pixels are, no pixels) send and receive the bytes the
  real images do, within 1%, so the sweep's model counts what the code sends.

  simulator_check.py SOURCE BUILD NORMAL_BENCH MPIEXEC RANKS [MPI flags...]
"""
import json
import os
import subprocess
import sys


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stdout}\n{result.stderr}")
    return result.stdout


def runs(path):
    return {(r["size"], r["mode"], r["algorithm"], r["rows"]): r
            for r in json.load(open(path))["runs"]}


def main():
    source, build, normal_bench, mpiexec, ranks = sys.argv[1:6]
    mpi_flags = sys.argv[6:]
    run(["cmake", "-S", source, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
         "-DTETRAY_SMPI=ON", "-DCMAKE_CXX_COMPILER=smpicxx", "-DTETRAY_WARNINGS_AS_ERRORS=ON"])
    run(["cmake", "--build", build])
    bench = os.path.join(build, "bin", "tetray-composite-bench")
    platforms = os.path.join(source, "tools", "composite_bench", "platforms")
    hosts = os.path.join(build, "hosts.txt")
    with open(hosts, "w") as f:
        f.write("here0\n" * int(ranks))
    settings = [f"--cfg={line.strip()}" for line in open(os.path.join(platforms, "this_machine.cfg"))
                if line.strip() and not line.startswith("#")]
    options = ["--sizes", "96", "131", "--ranks", ranks, "--repeat", "1", "--algorithms",
               "binary_swap", "radix_k", "gather", "automatic", "--rows", "natural", "interlaced",
               "--cost-size", "64"]
    smpirun = ["smpirun", "-no-privatize", "-np", ranks, "-hostfile", hosts, "-platform",
               os.path.join(platforms, "this_machine.xml"), "--cfg=smpi/host-speed:1Gf",
               "--cfg=smpi/send-is-detached-thresh:0"] + settings
    files = {name: os.path.join(build, f"check_{name}.json") for name in ("real", "sim", "model")}
    run([mpiexec, "-np", ranks] + mpi_flags + [normal_bench] + options + ["--json", files["real"]])
    run(smpirun + [bench] + options + ["--json", files["sim"]])
    run(smpirun + [bench] + options + ["--model", "--costs-ns", "1", "1", "1", "--json",
                                       files["model"]])
    real, sim, model = (runs(files[name]) for name in ("real", "sim", "model"))
    failures = []
    for key, r in real.items():
        if sim[key]["root_image_hash"] != r["root_image_hash"]:
            failures.append(f"{key}: simulator's image {sim[key]['root_image_hash']} "
                            f"!= real {r['root_image_hash']}")
        for figure in ("sent_max_bytes", "moved_mean_bytes", "moved_max_bytes"):
            if sim[key][figure] != r[figure]:
                failures.append(f"{key}: simulator's {figure} {sim[key][figure]} != real {r[figure]}")
            if abs(model[key][figure] - r[figure]) > 0.01 * r[figure]:
                failures.append(f"{key}: model's {figure} {model[key][figure]} is not within 1% "
                                f"of the real {r[figure]}")
    print(f"{len(real)} configurations at {ranks} ranks compared")
    if failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()

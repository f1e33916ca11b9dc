#!/usr/bin/env python3
"""Byte-for-byte regression of every output sonarsim writes, against a stored manifest of SHA-256 sums.

Renders each example scene with its own sensor, the device sensor, ground truth and (in the tank) multipath;
the three sampling schemes; and a small batch dataset with ARIS and MCAP files. Every file written is hashed;
timings (`time_ms`, index.csv's `ms`), the commit a dataset records and the ARIS file's creation date are taken
out before hashing, and
the repository's absolute path (mesh paths in the metadata) is replaced by a placeholder, everything else must match.

  golden.py SONARSIM ASSETS OUTDIR MANIFEST            compare (exit 1 listing every file that differs)
  golden.py SONARSIM ASSETS OUTDIR MANIFEST --update   rewrite the manifest (only when an image is meant to change)
  golden.py SONARSIM ASSETS OUTDIR MANIFEST --retake   this CPU maker's sums of an unchanged HEAD, whose
                                                       outputs another maker's manifest already holds

MANIFEST names the set kept beside it, one per CPU maker (MANIFEST.GenuineIntel.sha256,
MANIFEST.AuthenticAMD.sha256): images of meshes differ in their last bits between makers (cpu()). Each
manifest says which generation of the outputs it holds ("# outputs: N"). --update starts a new generation in
this machine's; the others are then stale until a machine of their maker retakes them (--retake). A stale
manifest, or none for this maker, cannot check anything: the comparison says so and exits 77 (skipped), where
a wrong one would fail every unchanged file.
"""
import hashlib
import json
import os
import shutil
import subprocess
import sys

# (name, scene file or None for the built-in scene, extra arguments)
CASES = [
    ("fig9", None, ["--ground-truth"]),
    ("fig9_device", None, ["--set", "sensor.model=device"]),
    ("fig9_pose2", "fig9_pose2.json", []),
    ("fig9_uniform", None, ["--set", "sampling.scheme=uniform"]),
    ("fig9_spread", None, ["--set", "sampling.scheme=spread"]),
    ("floor", "floor.json", ["--ground-truth"]),
    ("floor_device", "floor.json", ["--set", "sensor.model=device"]),
    ("shipwreck", "shipwreck.json", ["--ground-truth"]),
    ("shipwreck_device", "shipwreck.json", ["--set", "sensor.model=device", "--ground-truth"]),
    ("monterey", "monterey.json", []),
    ("monterey_device", "monterey.json", ["--set", "sensor.model=device"]),
    ("tank", "tank.json", ["--ground-truth"]),
    ("tank_direct", "tank.json", ["--set", "sampling.bounces=0"]),
    ("tank_b1_ideal", "tank.json", ["--set", "sampling.bounces=1", "--set", "sensor.model=ideal", "--ground-truth"]),
    ("tank_b2", "tank.json", ["--set", "sampling.bounces=2"]),
]
BATCH = ["--circle", "1.5,1.5,0,1.2,0.8,3", "--ground-truth", "--aris", "BATCHDIR/rec.aris", "--mcap",
         "BATCHDIR/rec.mcap", "--set", "sonar.beams=64", "--set", "sonar.frequency_khz=1800",
         "--set", "sonar.range_min_m=0.75", "--set", "export.start_time_s=1700000000",
         "--set", "sensor.model=device"]


def normalise(path, root):
    with open(path, "rb") as f:
        data = f.read()
    if path.endswith(".json"):  # timings vary; mesh paths are absolute, in whichever clone this runs
        doc = json.loads(data)
        doc.pop("time_ms", None)
        if isinstance(doc.get("program"), dict):  # dataset.json: the commit changes with every commit
            doc["program"].pop("commit", None)
        data = json.dumps(doc, sort_keys=True).replace(root, "<repository>").encode()
    elif path.endswith("index.csv"):  # the ms column is a timing
        rows = [line.split(",") for line in data.decode().splitlines()]
        col = rows[0].index("ms")
        data = "\n".join(",".join(r[:col] + r[col + 1:]) for r in rows).encode()
    elif path.endswith(".aris"):  # the file header's creation date (bytes 48..79) is the wall clock
        data = data[:48] + data[80:]
    return hashlib.sha256(data).hexdigest()


# Embree chooses its kernels by CPU (AVX2 or AVX-512 give hit distances that differ in the last bits): the sums
# are taken with AVX2 kernels on every machine that has them.
ENV = dict(os.environ, SONARSIM_EMBREE_CONFIG="isa=avx2")


def cpu():
    """The CPU maker and model: Embree's ray-triangle kernels use the processor's approximate reciprocal, whose
    last bits differ between makers, so hit distances (and every image of a mesh) differ in their last bits."""
    info = {}
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                k, _, v = line.partition(":")
                info.setdefault(k.strip(), v.strip())
    except OSError:
        pass
    return "%s %s" % (info.get("vendor_id", "?"), info.get("model name", "?"))


def vendor_manifest(path):
    """MANIFEST.VENDOR.sha256 beside the MANIFEST.sha256 named: one manifest per CPU maker (see cpu())."""
    root, ext = os.path.splitext(path)
    vendor = cpu().split()[0]
    return "%s.%s%s" % (root, vendor, ext)


def read_manifest(path):
    """(sums by file, header fields: cpu, outputs) of a manifest."""
    sums, header = {}, {"cpu": None, "outputs": 0}
    with open(path) as f:
        for line in f:
            if line.startswith("# cpu:"):
                header["cpu"] = line[len("# cpu:"):].strip()
            elif line.startswith("# outputs:"):
                header["outputs"] = int(line[len("# outputs:"):])
            elif line.strip():
                h, k = line.split(None, 1)
                sums[k.strip()] = h
    return sums, header


def newest_generation(manifest):
    """The newest outputs generation among the makers' manifests beside MANIFEST (its maker's, generation)."""
    root, ext = os.path.splitext(manifest)
    folder, stem = os.path.split(root)
    best = (None, 0)
    for name in sorted(os.listdir(folder or ".")):
        if name.startswith(stem + ".") and name.endswith(ext):
            maker = name[len(stem) + 1:-len(ext)]
            gen = read_manifest(os.path.join(folder, name))[1]["outputs"]
            if gen > best[1]:
                best = (maker, gen)
    return best


def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=ENV)
    if r.returncode != 0:
        sys.exit("golden: command failed: %s\n%s" % (" ".join(cmd), r.stdout.decode(errors="replace")))


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    exe, assets, out, named = sys.argv[1:5]
    manifest = vendor_manifest(named)
    update, retake = "--update" in sys.argv[5:], "--retake" in sys.argv[5:]
    newest_maker, newest = newest_generation(named)
    own = read_manifest(manifest)[1]["outputs"] if os.path.exists(manifest) else None
    if not (update or retake):
        if own is None:
            print("golden: skipped: no manifest for this CPU maker (%s); take one with --retake from an "
                  "unchanged HEAD" % manifest)
            sys.exit(77)
        if own < newest:
            print("golden: skipped: %s holds outputs generation %d, %s's holds %d (images changed since this "
                  "maker's sums were taken); retake them with --retake on this maker from an unchanged HEAD"
                  % (os.path.basename(manifest), own, newest_maker, newest))
            sys.exit(77)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    for i, (name, scene, extra) in enumerate(CASES):
        print("golden: [%d/%d] %s" % (i + 1, len(CASES) + 1, name), flush=True)
        cmd = [exe, "render", "--out", os.path.join(out, name)] + extra
        if scene:
            cmd += ["--scene", os.path.join(assets, "scenes", scene)]
        run(cmd)
    print("golden: [%d/%d] batch" % (len(CASES) + 1, len(CASES) + 1), flush=True)
    bdir = os.path.join(out, "batch")
    run([exe, "batch", "--out", bdir] + [a.replace("BATCHDIR", out) for a in BATCH])
    sums = {}
    for root, _, files in os.walk(out):
        for f in files:
            p = os.path.join(root, f)
            rel = os.path.relpath(p, out)
            if rel.endswith(".lock"):
                continue
            sums[rel] = normalise(p, os.path.dirname(os.path.abspath(assets)))
    if update or retake:
        before = read_manifest(manifest)[0] if own is not None else None
        if retake:  # the newest generation, as another maker took it
            gen = newest
        elif before == sums and own == newest:  # nothing changed
            gen = newest
        else:
            gen = newest + 1
        with open(manifest, "w") as f:
            f.write("# cpu: %s\n# outputs: %d\n" % (cpu(), gen))
            for k in sorted(sums):
                f.write("%s  %s\n" % (sums[k], k))
        print("golden: wrote %d sums to %s (outputs generation %d)" % (len(sums), manifest, gen))
        return
    want, header = read_manifest(manifest)
    taken_on = header["cpu"]
    bad = []
    for k in sorted(set(want) | set(sums)):
        if k not in sums:
            bad.append("missing  " + k)
        elif k not in want:
            bad.append("new      " + k)
        elif want[k] != sums[k]:
            bad.append("differs  " + k)
    if bad:
        print("golden: %d of %d files differ from %s:" % (len(bad), len(want), manifest))
        print("\n".join("  " + b for b in bad))
        if taken_on != cpu():
            print("golden: the manifest was taken on '%s', this machine is '%s': mesh scenes differ in their "
                  "last bits between CPU makers (Embree's approximate reciprocal); retake it with --update only "
                  "when HEAD's unchanged outputs differ the same way" % (taken_on, cpu()))
        sys.exit(1)
    print("golden: all %d files byte-identical" % len(want))


if __name__ == "__main__":
    main()

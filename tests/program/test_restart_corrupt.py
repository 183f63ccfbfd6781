#!/usr/bin/env python3
"""Issue 18 items 3 and 4: restart files that are missing, damaged or from
another parameter set.

Item 3: --restart falls back to restart.prev.bin, with a warning, when
restart.bin is missing or invalid; a stale restart.bin.tmp is removed at start.
Item 4: a corpus of damaged files (byte flips, truncation, and fields set to
bad values with the checksum recomputed so that the validation of each field
is what refuses them: NaN time, negative step, material id 999, output index
1e15, ...) and a file of another parameter set: each is refused with one line
on stderr that names the file and the problem, a status of 1 (no crash, no
signal).  Needs BOLIDE_BUILDDIR."""
import os
import shutil
import struct
import subprocess
import sys
import tempfile

B = os.environ["BOLIDE_BUILDDIR"]
M64 = (1 << 64) - 1


def checksum(buf):
    """restart_checksum (src/io/restart.h)."""
    h = 0xCBF29CE484222325
    n8 = len(buf) // 8 * 8
    for (w,) in struct.iter_unpack("<Q", buf[:n8]):
        h = ((h ^ w) * 0x100000001B3) & M64
        h ^= h >> 29
    for b in buf[n8:]:
        h = ((h ^ b) * 0x100000001B3) & M64
    return h


def layout(buf):
    """Offsets of the parts of a version-7 file (the far-field flag: the last
    8 bytes before the checksum when the file holds no far field)."""
    count = struct.unpack_from("<Q", buf, 72)[0]
    nf = struct.unpack_from("<i", buf, 128)[0]
    fields, pos = [], 132
    for _ in range(nf):
        name = buf[pos:pos + 32].split(b"\0")[0].decode()
        size = struct.unpack_from("<i", buf, pos + 32)[0]
        fields.append((name, size))
        pos += 36
    state = pos
    pos += 344
    plen = struct.unpack_from("<Q", buf, pos)[0]
    params = pos
    pos += 8 + plen
    cells = pos
    nc = struct.unpack_from("<q", buf, pos)[0]
    pos += 8 + 16 * nc
    arrays = {}
    for name, size in fields:
        arrays[name] = (pos, size)
        pos += size * count
    return dict(count=count, state=state, params=params, cells=cells, arrays=arrays, flaws=pos,
                grav=len(buf) - 16)


def reseal(buf):
    """Recompute the checksum of a modified file."""
    return buf[:-8] + struct.pack("<Q", checksum(buf[:-8]))


STATE = dict(time=0, dt=8, dt_next=16, step=24, updates=32, nr_removed=40, snap_index=48, next_out=56,
             next_stats=64, box=72, periodic=96, removed_m=104, start_E_tot=184, start_set=264,
             start_com=272, rebuild_h_max=296, need_rebuild=304, stats_offset=312, ti_current=320,
             nr_ranks=328, rank=336)


def main():
    work = tempfile.mkdtemp()
    os.chdir(work)
    fails = []
    subprocess.run([B + "/bolide-ic", "sod", "--nx", "16", "--size", "2,1,1", "-o", "sod.hdf5"],
                   check=True, stdout=subprocess.DEVNULL)
    with open("p.yml", "w") as f:
        f.write("InitialConditions:\n  file_name: sod.hdf5\n  periodic: true\nTimeIntegration:\n  time_end: 0.05\n"
                "  dt_max: 0.001\nSnapshots:\n  subdir: out\n  delta_time: 0.01\nScheduler:\n  deterministic: true\n"
                "Restarts:\n  enable: true\n  subdir: out/restart\n  delta_steps: 2\n")

    def bolide(*args):
        return subprocess.run([B + "/bolide", "-t", "1"] + list(args) + ["p.yml"], capture_output=True, text=True)

    r = bolide("-n", "5")
    if r.returncode:
        print(r.stdout[-500:], r.stderr)
        sys.exit("FAIL: the first run")
    R = "out/restart/"
    good = open(R + "restart.bin", "rb").read()
    good_prev = open(R + "restart.prev.bin", "rb").read()

    def put(name, data):
        with open(R + name, "wb") as f:
            f.write(data)

    def reset():
        for n in os.listdir(R):
            os.unlink(R + n)
        put("restart.bin", good)
        put("restart.prev.bin", good_prev)

    # ---- item 3: fallback and stale temporary files
    cases3 = [("restart.bin missing", lambda: os.unlink(R + "restart.bin")),
              ("restart.bin truncated", lambda: put("restart.bin", good[:5000])),
              ("restart.bin with a flipped byte", lambda: put("restart.bin", good[:900] + bytes([good[900] ^ 4]) + good[901:]))]
    for what, damage in cases3:
        reset()
        damage()
        r = bolide("--restart", "-n", "6")
        warn = [l for l in r.stderr.splitlines() if "previous restart file" in l]
        if r.returncode or not warn or "resumed from out/restart/restart.prev.bin at step 4" not in r.stdout:
            fails.append("fallback (%s): exit %d, stderr %r" % (what, r.returncode, r.stderr[-300:]))
        else:
            print("ok: fallback, %s: %s" % (what, warn[0]))
    reset()
    put("restart.bin.tmp", good[:1000])
    with open("out/snapshot_0007.hdf5.tmp", "wb") as f:
        f.write(b"partial")
    r = bolide("--restart", "-n", "6")
    if r.returncode or os.path.exists(R + "restart.bin.tmp") or "removed out/restart/restart.bin.tmp" not in r.stdout:
        fails.append("stale restart.bin.tmp not removed (exit %d)" % r.returncode)
    else:
        print("ok: stale restart.bin.tmp removed at start")
    if os.path.exists("out/snapshot_0007.hdf5.tmp") or "removed out/snapshot_0007.hdf5.tmp" not in r.stdout:
        fails.append("stale snapshot temporary file not removed")
    else:
        print("ok: stale snapshot_0007.hdf5.tmp removed at start")

    # ---- item 4: the corpus (restart.prev.bin removed: no fallback)
    L = layout(good)
    st, ar = L["state"], L["arrays"]

    def setf(buf, off, fmt, val):
        b = bytearray(buf)
        struct.pack_into(fmt, b, off, val)
        return reseal(bytes(b))

    nan = float("nan")
    corpus = []
    for k, off in enumerate([0, 17, 30, 75, 100, 140, st + 3, st + 100, L["params"] + 20, L["cells"] + 9,
                             ar["x"][0] + 5, ar["h"][0] + 7, ar["id"][0] + 1, len(good) // 2, len(good) - 9,
                             len(good) - 1]):
        corpus.append(("byte %d flipped" % off, good[:off] + bytes([good[off] ^ 0x20]) + good[off + 1:]))
    for n in (0, 10, 127, 135, 2000, len(good) // 3, len(good) - 8, len(good) - 1):
        corpus.append(("truncated to %d bytes" % n, good[:n]))
    corpus.append(("8 bytes appended", good + b"\0" * 8))
    corpus.append(("not a restart file", b"hello world\n" * 100))
    corpus.append(("format version 2", setf(good, 16, "<I", 2)))
    corpus.append(("format version 3 (before the far field)", setf(good, 16, "<I", 3)))
    corpus.append(("format version 5 (before the ranks)", setf(good, 16, "<I", 5)))
    corpus.append(("format version 6 (before the centre of mass)", setf(good, 16, "<I", 6)))
    corpus.append(("other byte order", setf(good, 20, "<I", 0x04030201)))
    corpus.append(("particle count 1e15", setf(good, 72, "<Q", 10 ** 15)))
    corpus.append(("parameter hash", setf(good, 80, "<Q", 12345)))
    corpus.append(("field count 3", setf(good, 128, "<i", 3)))
    corpus.append(("NaN time", setf(good, st + STATE["time"], "<d", nan)))
    corpus.append(("infinite time", setf(good, st + STATE["time"], "<d", float("inf"))))
    corpus.append(("time before time_begin", setf(good, st + STATE["time"], "<d", -1.0)))
    corpus.append(("time after time_end", setf(good, st + STATE["time"], "<d", 7.0)))
    corpus.append(("negative step", setf(good, st + STATE["step"], "<q", -5)))
    corpus.append(("NaN time step", setf(good, st + STATE["dt"], "<d", nan)))
    corpus.append(("zero next time step", setf(good, st + STATE["dt_next"], "<d", 0.0)))
    corpus.append(("output index 1e15", setf(good, st + STATE["next_out"], "<q", 10 ** 15)))
    corpus.append(("negative output index", setf(good, st + STATE["next_out"], "<q", -1)))
    corpus.append(("snapshot index 1e15", setf(good, st + STATE["snap_index"], "<q", 10 ** 15)))
    corpus.append(("negative box", setf(good, st + STATE["box"], "<d", -2.0)))
    corpus.append(("periodic flag 7", setf(good, st + STATE["periodic"], "<q", 7)))
    corpus.append(("NaN budget", setf(good, st + STATE["removed_m"], "<d", nan)))
    corpus.append(("NaN centre of mass", setf(good, st + STATE["start_com"], "<d", nan)))
    corpus.append(("rebuild h_max 0", setf(good, st + STATE["rebuild_h_max"], "<d", 0.0)))
    corpus.append(("rebuild flag 2", setf(good, st + STATE["need_rebuild"], "<q", 2)))
    corpus.append(("negative statistics offset", setf(good, st + STATE["stats_offset"], "<q", -3)))
    corpus.append(("integer time -1", setf(good, st + STATE["ti_current"], "<q", -1)))
    corpus.append(("integer time past the run", setf(good, st + STATE["ti_current"], "<q", 2 ** 57)))
    corpus.append(("0 ranks", setf(good, st + STATE["nr_ranks"], "<q", 0)))
    corpus.append(("rank 5 of 1", setf(good, st + STATE["rank"], "<q", 5)))
    corpus.append(("cell count 1e12", setf(good, L["cells"], "<q", 10 ** 12)))
    corpus.append(("NaN cell h_max", setf(good, L["cells"] + 8, "<d", nan)))
    corpus.append(("material id 999", setf(good, ar["mat"][0] + 4 * 10, "<i", 999)))
    corpus.append(("NaN smoothing length", setf(good, ar["h"][0] + 8 * 3, "<d", nan)))
    corpus.append(("negative mass", setf(good, ar["m"][0], "<d", -1.0)))
    corpus.append(("infinite velocity", setf(good, ar["vx"][0] + 8 * 7, "<d", float("inf"))))
    corpus.append(("negative density", setf(good, ar["rho"][0] + 8 * 2, "<d", -1.0)))
    corpus.append(("negative energy of an ideal gas", setf(good, ar["u"][0] + 8 * 4, "<d", -1.0)))
    corpus.append(("damage 2", setf(good, ar["dmg"][0], "<d", 2.0)))
    corpus.append(("negative id", setf(good, ar["id"][0], "<q", -7)))
    corpus.append(("duplicate id", setf(good, ar["id"][0] + 8, "<q", struct.unpack_from("<q", good, ar["id"][0])[0])))
    corpus.append(("rebuild position outside the box", setf(good, ar["x0"][0], "<d", 99.0)))
    corpus.append(("negative flaw count", setf(good, ar["n_flaws"][0], "<i", -1)))
    corpus.append(("time bin 99", setf(good, ar["time_bin"][0] + 4 * 6, "<i", 99)))
    corpus.append(("flaw count 1e18", setf(good, L["flaws"], "<Q", 10 ** 18)))
    corpus.append(("flaw offsets", setf(good, L["flaws"] + 8 + 8 * 5, "<q", 3)))
    corpus.append(("far-field flag 2", setf(good, L["grav"], "<q", 2)))
    corpus.append(("far-field flag without its data", setf(good, L["grav"], "<q", 1)))
    corpus.append(("empty file", b""))
    ok = 0
    for what, data in corpus:
        reset()
        os.unlink(R + "restart.prev.bin")
        put("restart.bin", data)
        r = bolide("--restart", "-n", "6")
        lines = r.stderr.strip().splitlines()
        if r.returncode != 1 or len(lines) != 1 or "restart" not in lines[0] or "error" not in lines[0]:
            fails.append("%s: exit %d, stderr %r" % (what, r.returncode, r.stderr[-400:]))
        else:
            ok += 1
            print("ok: %-34s %s" % (what + ":", lines[0]))
    # another parameter set: refused, naming the parameter
    reset()
    r = bolide("--restart", "-P", "SPH:resolution_eta:1.3")
    lines = r.stderr.strip().splitlines()
    if r.returncode != 1 or len(lines) != 1 or "resolution_eta" not in lines[0]:
        fails.append("other parameters: exit %d, stderr %r" % (r.returncode, r.stderr[-400:]))
    else:
        ok += 1
        print("ok: other parameters: %s" % lines[0])
    # the same parameters with other Restarts settings: accepted
    reset()
    r = bolide("--restart", "-n", "6", "-P", "Restarts:delta_steps:3")
    if r.returncode:
        fails.append("Restarts settings changed: refused: %r" % r.stderr[-300:])
    print("%d of %d damaged files and parameter sets refused cleanly" % (ok, len(corpus) + 1))
    for f in fails:
        print("FAIL: " + f)
    shutil.rmtree(work)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())

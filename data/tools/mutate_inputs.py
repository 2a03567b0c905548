#!/usr/bin/env python3
"""Bounded mutation run over radkit's loaders: mutated copies of data/ scenes and of meshes
derived from data/sphere-interior.off (OFF, ASCII and binary PLY, ASCII and binary STL, OBJ+MTL)
go through `radkit mesh` (every case), `radkit run` (every fourth, small mesh), `radkit render`
and `radkit photons` (every eighth each, small); with --all-commands also `run --method
hierarchical`, `formfactors` and `solvers` (every eighth each), `bench formfactors|path-trace`
(every sixteenth), `bench hierarchical` and `study` (every thirty-second). --options N then
adds N hostile-option cases over every command, `view` and `brdf` included (hostile_options.py),
and --readers N adds N cases of mutated files that other readers take: a run folder's files
(radiosity.vtp, report.json, surfaces.csv, convergence.csv, formfactors.bin, links.png) for
`view --screenshot` in three modes and for `photons --compare`, volume scenes for `clouds
--scene`, and PFM references for `render --reference`.
Each run has a time limit and its peak memory is measured (GNU time). Counts outcomes: success
(exit 0), clean error (non-zero exit with a message and no output), crash (a signal, an abort
or an uncaught exception), hang (time limit), memory (peak RSS over MEMORY_LIMIT_MB), silent
failure or error with output (none should occur), "non-finite output" (a successful run that
wrote nan or inf into a text file: a silent wrong result) and staging folders left behind. Exits 1
when any case is neither a success nor a clean error. The same --seed gives the same inputs.

  tests/viewer/xvfb_run.sh python3 data/tools/mutate_inputs.py --radkit build/apps/radkit \
      --cases 1000 --all-commands --options 600 --readers 300 --jobs 2 --work /tmp/mut
"""
import argparse, json, os, random, re, shutil, signal, struct, subprocess, sys

HOSTILE = ["nan", "-inf", "inf", "1e999", "-1", "0", "1e20", "4000000000", "-2147483648",
           "99999999999999", "1e-300", "0.5", "x", "", "3.0", "-0"]


def read_off(path):
    tokens = [l.split() for l in open(path) if l.strip() and not l.startswith("#")]
    nv, nf = int(tokens[1][0]), int(tokens[1][1])
    verts = [list(map(float, t[:3])) for t in tokens[2:2 + nv]]
    faces = [list(map(int, t[1:1 + int(t[0])])) for t in tokens[2 + nv:2 + nv + nf]]
    return verts, faces


def seeds(data):
    """(file name, bytes, kind) of every seed; kind 'scene' is given to radkit directly."""
    out = []
    for name in sorted(os.listdir(data)):
        if name.endswith(".json") and os.path.getsize(os.path.join(data, name)) < 200000:
            out.append((name, open(os.path.join(data, name), "rb").read(), "scene"))
    verts, faces = read_off(os.path.join(data, "sphere-interior.off"))
    off = "OFF\n%d %d 0\n" % (len(verts), len(faces)) + "".join("%r %r %r\n" % tuple(v) for v in verts) + \
          "".join("3 %d %d %d\n" % tuple(f) for f in faces)
    out.append(("m.off", off.encode(), "mesh"))
    head = "ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" \
           "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
    ply = head % ("ascii", len(verts), len(faces)) + "".join("%r %r %r\n" % tuple(v) for v in verts) + \
          "".join("3 %d %d %d\n" % tuple(f) for f in faces)
    out.append(("m.ply", ply.encode(), "mesh"))
    body = b"".join(struct.pack("<3f", *v) for v in verts) + b"".join(struct.pack("<B3i", 3, *f) for f in faces)
    out.append(("b.ply", (head % ("binary_little_endian", len(verts), len(faces))).encode() + body, "mesh"))
    stl = "solid s\n" + "".join("facet normal 0 0 0\nouter loop\n" + "".join("vertex %r %r %r\n" % tuple(verts[i]) for i in f) +
                                "endloop\nendfacet\n" for f in faces) + "endsolid s\n"
    out.append(("m.stl", stl.encode(), "mesh"))
    bstl = b"\0" * 80 + struct.pack("<I", len(faces)) + b"".join(
        struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *verts[i]) for i in f) + b"\0\0" for f in faces)
    out.append(("b.stl", bstl, "mesh"))
    obj = "mtllib m.mtl\n" + "".join("v %r %r %r\n" % tuple(v) for v in verts) + "g ball\nusemtl lamp\n" + \
          "".join("f %d %d %d\n" % (f[0] + 1, f[1] + 1, f[2] + 1) for f in faces)
    out.append(("m.obj", obj.encode(), "scene"))
    return out


def mutate(data, rng):
    """One to three random edits: byte flips, truncation, line deletion or duplication,
    a number replaced by a hostile value, a random chunk repeated, a number scaled a little."""
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        op = rng.randrange(7)
        if not data:
            break
        if op == 0:
            b = bytearray(data)
            for _ in range(rng.randint(1, 8)):
                b[rng.randrange(len(b))] = rng.randrange(256)
            data = bytes(b)
        elif op == 1:
            data = data[:rng.randrange(len(data))]
        elif op in (2, 3):
            lines = data.split(b"\n")
            k = rng.randrange(len(lines))
            if op == 2:
                del lines[k]
            else:
                lines.insert(k, lines[k])
            data = b"\n".join(lines)
        elif op == 4:
            nums = list(re.finditer(rb"-?\d+(\.\d+)?(e-?\d+)?", data))
            if nums:
                m = rng.choice(nums[:200] if rng.random() < 0.5 else nums)
                data = data[:m.start()] + rng.choice(HOSTILE).encode() + data[m.end():]
        elif op == 5:
            a = rng.randrange(len(data))
            data = data[:a] + data[a:a + rng.randint(1, 64)] * rng.randint(2, 5) + data[a:]
        else:  # a plausible value: a number scaled a little, so many cases still load
            nums = list(re.finditer(rb"\d+\.\d+", data))
            if nums:
                m = rng.choice(nums)
                value = float(m.group()) * rng.uniform(0.5, 1.5)
                data = data[:m.start()] + ("%.6g" % value).encode() + data[m.end():]
    return data


# A run whose peak resident memory passes this is counted as "memory": radkit itself takes
# about 50 MB, and no seed here (scenes under 200 kB, meshes of 320 faces, terrain-51k.off of
# 5 MB) justifies more than a few hundred.
MEMORY_LIMIT_MB = 1024


def run_radkit(radkit, argv, cwd, timeout):
    """(exit code or None on time-out, stdout + stderr, peak RSS in MB) of one run under GNU
    time; a run past the limit is killed with its whole process group."""
    p = subprocess.Popen(["/usr/bin/time", "-q", "-f", "\n@maxrss %M", radkit] + argv, cwd=cwd,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return None, "", 0.0
    text = (out + err).decode(errors="replace")
    m = re.search(r"\n@maxrss (\d+)\s*$", text)
    rss = int(m.group(1)) / 1024.0 if m else 0.0
    return p.returncode, text[:m.start()] if m else text, rss


NON_FINITE = re.compile(rb"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def non_finite_output(case, written):
    """The first written text file (.csv .json .md .mtx .txt) holding nan or inf, or None."""
    paths = []
    for w in written:
        p = os.path.join(case, w)
        if os.path.isdir(p):
            paths += [os.path.join(p, f) for f in sorted(os.listdir(p))]
        elif os.path.isfile(p):
            paths.append(p)
    for p in paths:
        if p.endswith((".csv", ".json", ".md", ".mtx", ".txt")) and os.path.isfile(p):
            if NON_FINITE.search(open(p, "rb").read()):
                return p
    return None


def classify(rc, output):
    if rc < 0 or rc >= 128 or "terminate called" in output or "Assertion" in output:
        return "crash"  # a signal, an abort or an uncaught exception
    if rc == 0:
        return "success"
    # radkit's own errors say "error"; CLI11's parse errors name the option ("--k: Value 1 not in
    # range [2 - 100000]") and end with "Run with --help".
    return "clean error" if "error" in output.lower() or "Run with --help" in output else "silent failure"


def run_and_count(args, cmd, case, label, written, log_tag, counts, cases, peak):
    """Runs one command in `case` and counts its outcome under `label`: a hang, a crash, a clean
    error, an error that left any of `written` behind, a success that wrote nan or inf into one
    of them, or memory over the limit. Cases worth a look are appended to `cases`."""
    rc, text, rss = run_radkit(args.radkit, cmd, case, args.timeout)
    outcome = "hang" if rc is None else classify(rc, text)
    if rc not in (None, 0) and written and os.path.exists(os.path.join(case, written[0])):
        outcome = "error with output"
    if outcome == "success" and written and non_finite_output(case, written):
        outcome = "non-finite output"
    if rss > MEMORY_LIMIT_MB:
        outcome = "memory"
    peak[label] = max(peak.get(label, 0.0), rss)
    if args.log:
        first = next((l for l in text.splitlines() if "error" in l.lower()), "")
        with open(args.log, "a") as log:
            log.write("%s\t%s\t%s\t%s\t%.0f MB\t%s\n" % (case, log_tag, label, outcome, rss, first[:300]))
    counts[(label, outcome)] = counts.get((label, outcome), 0) + 1
    if outcome not in ("success", "clean error"):
        cases.append("%s %s %s: %s (exit %s)" % (case, label, log_tag, outcome, rc))


RUN_FILES = ["radiosity.vtp", "report.json", "surfaces.csv", "convergence.csv", "formfactors.bin"]


def run_reader_cases(args, rng, counts, cases, peak):
    """Mutated inputs of the readers that do not load scenes; see the module's docstring."""
    work = os.path.join(args.work, "readers")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    cornell = os.path.abspath(os.path.join(args.data, "cornell-box.json"))
    made = [["run", cornell, "--patches", "60", "--no-render", "--out", "dense"],
            ["run", cornell, "--method", "hierarchical", "--epsilon", "1e-2", "--no-render", "--out", "hier"],
            ["render", cornell, "--patches", "60", "--size", "24x24", "--out", "ref.pfm"]]
    for cmd in made:
        rc, text, _ = run_radkit(args.radkit, cmd, work, 300)
        if rc != 0:
            raise SystemExit("could not make the reader seeds: radkit %s: %s" % (" ".join(cmd), text))
    volumes = sorted(f for f in os.listdir(os.path.join(args.data, "clouds")) if f.endswith(".json"))
    display = bool(os.environ.get("DISPLAY"))
    for n in range(args.readers):
        case = os.path.join(work, "case%04d" % n)
        os.makedirs(case)
        kind = n % 4
        if kind in (0, 1):  # a run folder: one file mutated (links.png only in the hierarchical one)
            source = "hier" if kind == 1 else "dense"
            shutil.copytree(os.path.join(work, source), os.path.join(case, "run"))
            files = [f for f in RUN_FILES + ["links.png"] if os.path.exists(os.path.join(case, "run", f))]
            target = os.path.join(case, "run", rng.choice(files))
            data = open(target, "rb").read()
            with open(target, "wb") as f:
                f.write(mutate(data, rng))
            mode = ["radiosity", "matrix", "convergence"][(n // 4) % 3]
            commands = [["view", "run", "--screenshot", "s.png", "--size", "64x48", "--mode", mode]] if display else []
            if n % 8 == 0:
                commands.append(["photons", cornell, "--patches", "60", "--photons", "2000", "--no-image",
                                 "--bench-rays", "0", "--compare", "run", "--out", "o-photons"])
        elif kind == 2:
            name = volumes[(n // 4) % len(volumes)]
            data = open(os.path.join(args.data, "clouds", name), "rb").read()
            with open(os.path.join(case, name), "wb") as f:
                f.write(mutate(data, rng))
            commands = [["clouds", "--scene", name, "--width", "16", "--height", "8", "--samples", "1",
                         "--primary-steps", "8", "--out", "o-clouds"]]
        else:
            data = open(os.path.join(work, "ref.pfm"), "rb").read()
            with open(os.path.join(case, "ref.pfm"), "wb") as f:
                f.write(mutate(data, rng))
            commands = [["render", cornell, "--patches", "60", "--size", "24x24", "--reference", "ref.pfm",
                         "--report", "r.json", "--out", "o.pfm"]]
        for cmd in commands:
            label = "reader-" + cmd[0] + ("-" + cmd[-1] if cmd[0] == "view" else "")
            out = cmd[cmd.index("--out") + 1] if "--out" in cmd else (cmd[cmd.index("--screenshot") + 1])
            written = [out] + (["r.json"] if "--report" in cmd else [])
            run_and_count(args, cmd, case, label, written, "reader", counts, cases, peak)
        if not cases or not cases[-1].startswith(case + " "):
            shutil.rmtree(case)
    if not display:
        counts[("reader-view", "no display")] = args.readers // 2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radkit", required=True)
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), ".."))
    ap.add_argument("--cases", type=int, default=400)
    ap.add_argument("--timeout", type=float, default=30)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--work", default="/tmp/radkit-mutate")
    ap.add_argument("--log", help="write each case's outcome and first error line here")
    ap.add_argument("--all-commands", action="store_true",
                    help="also run formfactors, solvers, run --method hierarchical, study and bench on the inputs")
    ap.add_argument("--options", type=int, default=0,
                    help="then this many hostile-option cases over every command (hostile_options.py; view "
                         "needs DISPLAY: run under tests/viewer/xvfb_run.sh)")
    ap.add_argument("--jobs", type=int, default=1, help="parallel runs of the hostile-option cases")
    ap.add_argument("--readers", type=int, default=0,
                    help="then this many cases of mutated run folders, volume scenes and PFM references")
    args = ap.parse_args()
    args.radkit = os.path.abspath(args.radkit)
    rng = random.Random(args.seed)
    base = seeds(args.data)
    mtl = b"newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n"
    counts, cases, peak = {}, [], {}
    for n in range(args.cases):
        name, text, kind = base[n % len(base)]
        case = os.path.join(args.work, "case%04d" % n)
        shutil.rmtree(case, ignore_errors=True)
        os.makedirs(case)
        mutated = mutate(text, rng)
        with open(os.path.join(case, name), "wb") as f:
            f.write(mutated)
        for mesh in ("sphere-interior.off", "terrain-51k.off"):  # meshes the data scenes name
            os.symlink(os.path.abspath(os.path.join(args.data, mesh)), os.path.join(case, mesh))
        with open(os.path.join(case, "m.mtl"), "wb") as f:
            f.write(mutate(mtl, rng) if name == "m.obj" and rng.random() < 0.3 else mtl)
        target = name
        if kind == "mesh":
            target = "scene.json"
            with open(os.path.join(case, target), "w") as f:
                json.dump({"materials": {"lamp": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
                           "surfaces": [{"name": "m", "material": "lamp", "mesh": name}]}, f)
        commands = [["mesh", target, "--out", "o-mesh"]]
        if n % 4 == 0:
            commands.append(["run", target, "--patches", "60", "--no-render", "--out", "o-run"])
        if n % 8 == 1:
            commands.append(["render", target, "--size", "24x24", "--spp", "2", "--out", "o-render.png"])
        if n % 8 == 5:
            commands.append(["photons", target, "--photons", "2000", "--no-radiosity", "--no-image",
                             "--bench-rays", "0", "--out", "o-photons"])
        if args.all_commands:  # the commands the first runs did not reach, on the same inputs
            if n % 8 == 2:
                commands.append(["run", target, "--method", "hierarchical", "--epsilon", "1e-2", "--hr-rays", "4",
                                 "--no-render", "--out", "o-hier"])
            if n % 8 == 3:
                commands.append(["formfactors", target, "--patches", "24", "--out", "o-ff"])
            if n % 8 == 6:
                commands.append(["solvers", target, "--patches", "24", "--out", "o-solvers"])
            if n % 16 == 7:
                commands.append(["bench", "formfactors", target, "--patches", "24", "--reference-rays", "1000"])
            if n % 16 == 15:
                commands.append(["bench", "path-trace", target, "--patches", "24", "--spp", "1"])
            if n % 32 == 11:
                commands.append(["bench", "hierarchical", target, "--epsilon", "1e-2", "--dense-patches", "24"])
            if n % 32 == 27:
                commands.append(["study", target, "--max-seconds", "1", "--knob-patches", "250", "--epsilons",
                                 "1e-2", "--out", "o-study"])
        for cmd in commands:
            label = cmd[0] if cmd[0] != "bench" else "bench-" + cmd[1]
            if "hierarchical" in cmd and cmd[0] == "run":
                label = "run-hierarchical"
            written = [cmd[-1]] if cmd[-2] == "--out" else []
            run_and_count(args, cmd, case, label, written, name, counts, cases, peak)
        left = [e for e in os.listdir(case) if ".partial-" in e or ".old-" in e]
        if left:
            counts[("staging", "left behind")] = counts.get(("staging", "left behind"), 0) + 1
        elif not cases or not cases[-1].startswith(case + " "):
            shutil.rmtree(case)  # keep only the cases worth looking at
    mutated_runs = sum(v for (c, _), v in counts.items() if c != "staging")
    options_ran = 0
    if args.options:
        import hostile_options
        log = open(args.log, "a") if args.log else None
        options_ran = hostile_options.run_cases(args.radkit, args.work, args.data, args.options, args.seed,
                                                args.timeout, args.jobs, counts, cases, log, peak=peak)
    if args.readers:
        run_reader_cases(args, rng, counts, cases, peak)
    total = sum(v for (c, o), v in counts.items() if c != "staging" and o != "no display")
    print("mutated inputs: %d (%d command runs); hostile-option cases: %d; command runs in all: %d"
          % (args.cases, mutated_runs, options_ran, total))
    outcomes = sorted({o for (c, o) in counts if c != "staging"}, key=lambda o: (o not in ("clean error", "success"), o))
    print("  %-19s %s  %s" % ("command", "  ".join("%11s" % o for o in outcomes), "peak MB"))
    for command in sorted({c for (c, _) in counts if c != "staging"}):
        print("  %-19s %s  %7.0f" % (command, "  ".join("%11d" % counts.get((command, o), 0) for o in outcomes),
                                      peak.get(command, 0)))
    if ("staging", "left behind") in counts:
        print("  staging folders left behind: %d" % counts[("staging", "left behind")])
    for line in cases:
        print("  " + line)
    return 1 if cases else 0


if __name__ == "__main__":
    sys.exit(main())

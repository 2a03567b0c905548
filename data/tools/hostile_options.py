#!/usr/bin/env python3
"""Hostile options for every radkit command (issue 20): each case is one command with small
settings (tiny scenes, 24 patches, 16x16 images) and one or two options set to a hostile value
(NaN, infinities, 1e999, -1, 0, huge counts, empty text, unknown names, wrong types, an existing
file or a missing folder for --out, a run folder of another scene for --compare, mutated run
folders and PFM references, ...); one case in five also runs on a mutated scene. Outcomes are
counted per command as in mutate_inputs.py. `view` runs only with an X display (run the script
under tests/viewer/xvfb_run.sh); without one its cases are left out and say so.

  tests/viewer/xvfb_run.sh python3 data/tools/hostile_options.py --radkit build/apps/radkit \\
      --cases 600 --work /tmp/hostile
Also used by `mutate_inputs.py --options N`.
"""
import argparse, concurrent.futures, os, random, shutil, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mutate_inputs  # noqa: E402

NUMBER = ["nan", "inf", "-inf", "1e999", "-1e999", "-1", "0", "-0", "1e-300", "4000000000",
          "99999999999999999999", "2147483648", "", "x", "1,2", "0x10", "3.5", "1e20"]
SIZES = ["0x0", "nanxnan", "-16x16", "16x", "x16", "100000x100000", "16x16x16", "1e3x1e3", "16X16",
         "4000000000x1", "16x0", "", "abc", "1x1"]
SOLVERS = ["sor:omega=nan", "sor:omega=2", "sor:omega=-1", "sor:omega=1e999", "sor:omega=0", "bogus",
           "jacobi:foo=1", "", ",", "jacobi,jacobi", "sor:omega", "sor:=1", "southwell;x",
           "sor:omega=1.2;power_iterations=-5", "sor:power_iterations=1e12", "sor:power_iterations=nan",
           "cg:x=1", "southwell", "cg", "jacobi,gauss-seidel,sor,southwell,cg"]
BUDGETS = ["1KiB", "0B", "-1GiB", "8XB", "1e999GiB", "nanGiB", "1B", "", "GiB", "1e-300B", "100"]
NAMES = ["bogus", "", "Jacobi", "1", "nan"]


def fixtures(radkit, work, data):
    """Scenes, two run folders of different scenes, PFM references and decoys in work/fix."""
    fix = os.path.join(work, "fix")
    if os.path.exists(os.path.join(fix, "ready")):
        return fix
    shutil.rmtree(fix, ignore_errors=True)
    os.makedirs(os.path.join(fix, "empty-folder"))
    for scene in ("furnace.json", "cube-one-emitter.json", "parallel-squares.json"):
        shutil.copy(os.path.join(data, scene), fix)
    def run(*args):
        subprocess.run([radkit] + list(args), cwd=fix, check=True, capture_output=True, timeout=300)
    run("run", "furnace.json", "--patches", "24", "--size", "16x16", "--out", "run-furnace")
    run("run", "cube-one-emitter.json", "--patches", "24", "--size", "16x16", "--out", "run-cube")
    run("run", "furnace.json", "--method", "hierarchical", "--epsilon", "1e-2", "--hr-rays", "4",
        "--size", "16x16", "--out", "run-hier")
    run("render", "furnace.json", "--shading", "radiosity", "--patches", "24", "--size", "16x16", "--out", "ref16.pfm")
    run("render", "furnace.json", "--shading", "radiosity", "--patches", "24", "--size", "32x32", "--out", "ref32.pfm")
    with open(os.path.join(fix, "notes.txt"), "w") as f:
        f.write("not an image, not a scene\n")
    open(os.path.join(fix, "ready"), "w").close()
    return fix


def mutated_run_folder(fix, case, rng):
    """A copy of run-furnace (or run-hier) with one file mutated, deleted or emptied."""
    src = os.path.join(fix, rng.choice(["run-furnace", "run-furnace", "run-hier"]))
    dst = os.path.join(case, "run-mut")
    shutil.copytree(src, dst)
    name = rng.choice(sorted(os.listdir(dst)))
    path = os.path.join(dst, name)
    how = rng.random()
    if how < 0.1:
        os.remove(path)
    elif how < 0.2:
        open(path, "wb").close()
    else:
        data = open(path, "rb").read()
        with open(path, "wb") as f:
            f.write(mutate_inputs.mutate(data, rng))
    return "run-mut"


def mutated_pfm(fix, case, rng):
    data = open(os.path.join(fix, "ref16.pfm"), "rb").read()
    with open(os.path.join(case, "ref-mut.pfm"), "wb") as f:
        f.write(mutate_inputs.mutate(data, rng))
    return "ref-mut.pfm"


def out_value(rng, kind):
    """Hostile --out: an existing file, an existing folder, a missing parent, empty, a decoy."""
    return rng.choice({"folder": ["notes.txt", "empty-folder", "notes.txt/o", "", ".", "furnace.json",
                                  "run-cube"],
                       "image": ["notes.txt", "empty-folder", "notes.txt/o.png", "missing-folder/o.png", "", "o.bmp", "o",
                                 "furnace.json"]}[kind])


# Options where a generic number within the documented range asks for a long run by design (a
# study budget of 1e20 s runs every rung): only their own pool, whose values must be refused or quick.
OWN_POOL_ONLY = {("study", "--max-seconds")}


def pick(rng, pool, key=None):
    """A value of the option's own pool, or (one time in three) any hostile number."""
    return rng.choice(NUMBER) if rng.random() < 0.33 and key not in OWN_POOL_ONLY else rng.choice(pool)


# command -> (base arguments with SCENE and OUT placeholders, {option: pool}, output kind)
COMMANDS = {
    "mesh": (["SCENE", "--patches", "24", "--out", "OUT"],
             {"--max-area": ["1e-12", "1e300", "0.01"], "--patches": ["10000001", "1"], "--out": "folder"}, "folder"),
    "formfactors": (["SCENE", "--patches", "24", "--out", "OUT"],
                    {"--ff": NAMES + ["monte-carlo", "hemisphere"], "--ff-samples": ["2147483648", "1", "100000"],
                     "--seed": ["-1", "18446744073709551616"], "--ff-enforce": NAMES + ["reciprocity"],
                     "--ff-storage": NAMES + ["float"], "--memory-budget": BUDGETS, "--preset": NAMES,
                     "--out": "folder"}, "folder"),
    "solvers": (["SCENE", "--patches", "24", "--solvers", "jacobi,southwell,cg", "--out", "OUT"],
                {"--solvers": SOLVERS, "--tol": ["1e-300", "1", "2"], "--max-iterations": ["1", "2147483648"],
                 "--max-seconds": ["1e-300", "1e300"], "--residual-norm": NAMES + ["per-patch"], "--out": "folder"},
                "folder"),
    "run": (["SCENE", "--patches", "24", "--no-render", "--out", "OUT"],
            {"--size": SIZES, "--image-size": ["15", "8193", "16"], "--adaptive-max-patches": ["0", "10000001", "30"],
             "--adaptive-tol": ["1e-300", "1e300"], "--adaptive-rounds": ["1000000", "2"], "--preset": NAMES + ["draft"],
             "--solvers": SOLVERS, "--tol": ["1e-300"], "--max-iterations": ["1"], "--method": NAMES,
             "--out": "folder", "--adaptive": None, "--photometric": None, "--smooth": None}, "folder"),
    "run-hierarchical": (["SCENE", "--method", "hierarchical", "--epsilon", "1e-2", "--hr-rays", "4", "--no-render",
                          "--out", "OUT"],
                         {"--epsilon": ["1", "0.999", "1e-300", "1e-9"], "--min-area": ["1e-300", "1e300", "1e-12"],
                          "--hr-rays": ["4097", "1", "2147483648"], "--hr-rounds": ["9", "8", "1"],
                          "--gather": NAMES + ["gauss-seidel"], "--link-colour": NAMES + ["power"],
                          "--tol": ["1e-300", "1"], "--max-iterations": ["1", "2"], "--max-seconds": ["1e-300"],
                          "--patches": ["24"], "--solvers": ["jacobi"], "--preset": ["draft"],
                          "--size": SIZES, "--image-size": ["16", "0"], "--out": "folder", "--adaptive": None},
                         "folder"),
    "render": (["SCENE", "--patches", "24", "--size", "16x16", "--spp", "1", "--photons", "2000", "--out", "OUT"],
               {"--shading": NAMES + ["radiosity", "phong", "cook-torrance", "path-trace", "photon-map", "final-gather"],
                "--size": SIZES, "--spp": ["1048577", "1"], "--photons": ["1", "18446744073709551616"],
                "--exposure": ["1e300", "1e-300"], "--tonemap": NAMES + ["filmic"], "--crease-angle": ["181", "180"],
                "--smooth-error": ["1e300"], "--reference": ["REF"], "--report": ["notes.txt", "empty-folder",
                                                                                  "notes.txt/r.json", "missing-folder/r.json"],
                "--g": NAMES + ["schlick"], "--sampler": NAMES + ["independent"], "--out": "image",
                "--smooth": None, "--compensated": None, "--unguided": None}, "image"),
    "photons": (["SCENE", "--patches", "24", "--photons", "2000", "--no-image", "--bench-rays", "0", "--out", "OUT"],
                {"--photons": ["4000000001", "1"], "--k": ["1", "100001", "2"], "--filter": NAMES + ["cone"],
                 "--seed": ["-1"], "--gather": ["4097", "0"], "--view": NAMES + ["map"],
                 "--size": SIZES, "--image-size": ["15", "8193"], "--compare": ["COMPARE"], "--bench-rays": ["1000000001", "1"],
                 "--out": "folder", "--no-radiosity": None}, "folder"),
    "view": (["RUN", "--screenshot", "OUT", "--size", "64x48"],
             {"RUN": ["RUN"], "--mode": ["formfactors-row:99999", "formfactors-row:-1", "formfactors-row:x",
                                         "formfactors-row:", "formfactors-row:1", "bogus", "", "matrix", "convergence",
                                         "false-colour", "formfactors-row:1e999"],
              "--size": SIZES, "--channel": NAMES + ["r", "g", "b"], "--exposure": ["1e300", "1e-300"],
              "--out": "folder", "--screenshot": "image", "--smooth": None, "--photometric": None}, "image"),
    "study": (["SCENE", "--max-seconds", "1", "--knob-patches", "250", "--epsilons", "1e-2", "--out", "OUT"],
              {"--max-seconds": ["1e-300", "0.001", "nan", "inf", "-1", "", "x"], "--knob-patches": ["249", "4000"], "--seed": ["-1"],
               "--epsilons": ["1", "1e-300"], "--out": "folder"}, "folder"),
    "bench-formfactors": (["bench", "formfactors", "SCENE", "--patches", "24", "--reference-rays", "1000"],
                          {"--reference-rays": ["9223372036854775808", "1"], "--ff-samples": ["2147483648", "1"],
                           "--ff": NAMES, "--memory-budget": BUDGETS, "--patches": ["10000001"]}, None),
    "bench-path-trace": (["bench", "path-trace", "SCENE", "--patches", "24", "--spp", "1"],
                         {"--spp": ["2147483648", "1"], "--max-area": ["1e-300"]}, None),
    "bench-solver": (["bench", "solver", "--n", "64", "--repetitions", "1", "--threads", "1"],
                     {"--n": ["63", "65537", "64"], "--repetitions": ["2147483648", "1"], "--threads": ["1000000", "2"]},
                     None),
    "bench-hierarchical": (["bench", "hierarchical", "SCENE", "--epsilon", "1e-2", "--dense-patches", "24"],
                           {"--epsilon": ["1", "1e-300"], "--dense-patches": ["10000001", "1"]}, None),
    "brdf": ([], {"--model": NAMES, "--alpha": ["1.0001", "1e-300"], "--mu": ["1.0001", "1e-300"],
                  "--g": NAMES, "--compensated": None, "--table": None}, None),
}
# Relative frequency: slow commands run less often, so 1000 cases fit in about ten minutes.
WEIGHTS = {"mesh": 3, "formfactors": 3, "solvers": 3, "run": 3, "run-hierarchical": 3, "render": 4, "photons": 3,
           "view": 4, "study": 1, "bench-formfactors": 2, "bench-path-trace": 2, "bench-solver": 2,
           "bench-hierarchical": 1, "brdf": 2}
SCENES = ["furnace.json", "cube-one-emitter.json", "parallel-squares.json"]


def make_case(rng, fix, case, seeds):
    """Writes the case's inputs into `case`; returns (command label, argv without radkit, out path)."""
    label = rng.choices(list(WEIGHTS), weights=list(WEIGHTS.values()))[0]
    base, options, kind = COMMANDS[label]
    args = list(base)
    if label in ("mesh", "formfactors", "solvers", "run", "run-hierarchical", "render", "photons", "study"):
        args.insert(0, label.split("-")[0])
    elif label in ("view", "brdf"):
        args.insert(0, label)
    scene = os.path.join(fix, rng.choice(SCENES))
    if rng.random() < 0.2 and "SCENE" in args:  # a mutated scene with hostile options
        name, text, _ = rng.choice([s for s in seeds if s[2] == "scene" and s[0].endswith(".json")])
        scene = os.path.join(case, name)
        with open(scene, "wb") as f:
            f.write(mutate_inputs.mutate(text, rng))
    out = {"folder": "o", "image": "o.png", None: None}[kind]
    chosen = rng.sample(sorted(options), min(len(options), rng.choice([1, 1, 2])))
    values = {}
    for name in chosen:
        pool = options[name]
        if pool is None:
            values[name] = None
        elif isinstance(pool, str):
            values[name] = out_value(rng, pool)
            decoy = os.path.join(case, values[name])
            if values[name].startswith("notes.txt/"):  # a folder inside a file: cannot be created
                shutil.copy(os.path.join(fix, "notes.txt"), os.path.join(case, "notes.txt"))
            if values[name] in ("notes.txt", "furnace.json"):
                shutil.copy(os.path.join(fix, values[name]), decoy)
            elif values[name] in ("empty-folder", "run-cube"):
                shutil.copytree(os.path.join(fix, values[name]), decoy)
        elif name == "--report":
            values[name] = pick(rng, pool, (label, name))
            shutil.copy(os.path.join(fix, "notes.txt"), os.path.join(case, "notes.txt"))
        elif pool == ["REF"]:
            values[name] = rng.choice([os.path.join(fix, "ref16.pfm"), os.path.join(fix, "ref32.pfm"),
                                       os.path.join(fix, "notes.txt"), "missing.pfm", "MUT", "MUT"])
            if values[name] == "MUT":
                values[name] = mutated_pfm(fix, case, rng)
        elif pool == ["COMPARE"]:
            values[name] = rng.choice([os.path.join(fix, "run-cube"), os.path.join(fix, "run-furnace"),
                                       os.path.join(fix, "empty-folder"), os.path.join(fix, "notes.txt"),
                                       "missing-folder", "", "MUT", "MUT"])
            if values[name] == "MUT":
                values[name] = mutated_run_folder(fix, case, rng)
        elif pool == ["RUN"]:
            values[name] = rng.choice([os.path.join(fix, "run-cube"), os.path.join(fix, "empty-folder"),
                                       os.path.join(fix, "notes.txt"), "missing-folder", "", "MUT", "MUT", "MUT"])
            if values[name] == "MUT":
                values[name] = mutated_run_folder(fix, case, rng)
        else:
            values[name] = pick(rng, pool, (label, name))
    run_dir = values.pop("RUN", os.path.join(fix, rng.choice(["run-furnace", "run-hier"])))
    argv = []
    for a in args:
        if a == "SCENE":
            argv.append(scene)
        elif a == "RUN":
            argv.append(run_dir)
        elif a == "OUT":
            # view's --out names the run folder written for a scene; its image is --screenshot
            hostile = values.pop("--screenshot" if label == "view" else "--out", None)
            argv.append(out if hostile is None else hostile)
        else:
            argv.append(a)
    for name, value in values.items():  # a repeated option: the later one wins in CLI11
        if name in argv and value is not None:
            i = argv.index(name)
            argv[i + 1] = value
        elif value is None:
            argv.append(name)
        else:
            argv += [name, value]
    if out and out not in argv:
        out = None  # the hostile --out replaced ours: a decoy that must stay as it was
    return label, argv, out


def snapshot(path):
    """What a decoy --out looked like, so an error that touched it is caught."""
    if os.path.isfile(path):
        return ("file", open(path, "rb").read())
    if os.path.isdir(path):
        return ("dir", sorted(os.listdir(path)))
    return None


def run_case(radkit, case, label, argv, out, timeout):
    decoys = [p for p in argv if os.path.isabs(p) and "/fix/" in p] + \
             [os.path.join(case, p) for p in ("notes.txt", "furnace.json", "empty-folder", "run-cube") if p in argv]
    fix_state = {p: snapshot(p) for p in decoys}
    rc, text, rss = mutate_inputs.run_radkit(radkit, argv, case, timeout)
    if rc is None:
        outcome = "hang"
    else:
        outcome = mutate_inputs.classify(rc, text)
        if rc != 0 and out and os.path.exists(os.path.join(case, out)):
            outcome = "error with output"
        if rc != 0 and any(snapshot(q) != s for q, s in fix_state.items()):
            outcome = "error with output"
    if rss > mutate_inputs.MEMORY_LIMIT_MB:
        outcome = "memory"
    left = [e for e in os.listdir(case) if ".partial-" in e or ".old-" in e]
    lines = text.strip().splitlines()
    first = next((l for l in lines if "error" in l.lower()), lines[-1] if lines else "")
    return outcome, first[:300], bool(left), rss


def run_cases(radkit, work, data, n, seed, timeout, jobs, counts, problems, log=None, offset=0, peak=None):
    """Runs n hostile-option cases; adds to counts[(command, outcome)], problems and
    peak[command] (largest peak RSS in MB)."""
    peak = {} if peak is None else peak
    rng = random.Random(seed * 7919 + 17)
    fix = fixtures(radkit, work, data)
    seeds = mutate_inputs.seeds(data)
    display = bool(os.environ.get("DISPLAY"))
    cases = []
    for k in range(n):
        case = os.path.join(work, "opt%04d" % (k + offset))
        shutil.rmtree(case, ignore_errors=True)
        os.makedirs(case)
        label, argv, out = make_case(rng, fix, case, seeds)
        if label == "view" and not display:
            counts[("view", "no display")] = counts.get(("view", "no display"), 0) + 1
            shutil.rmtree(case)
            continue
        cases.append((case, label, argv, out))
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        results = list(pool.map(lambda c: run_case(radkit, c[0], c[1], c[2], c[3], timeout), cases))
    for (case, label, argv, out), (outcome, first, left, rss) in zip(cases, results):
        counts[(label, outcome)] = counts.get((label, outcome), 0) + 1
        peak[label] = max(peak.get(label, 0.0), rss)
        if left:
            counts[("staging", "left behind")] = counts.get(("staging", "left behind"), 0) + 1
        line = "%s %s: %s | %.0f MB | radkit %s | %s" % (
            case, label, outcome, rss, " ".join(repr(a) if a == "" or " " in a else a for a in argv), first)
        if log:
            log.write(line + "\n")
        if outcome not in ("success", "clean error") or left:
            problems.append(line)
        else:
            shutil.rmtree(case)
    return len(cases)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--radkit", required=True)
    ap.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--cases", type=int, default=600)
    ap.add_argument("--timeout", type=float, default=30)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--work", default="/tmp/radkit-hostile")
    ap.add_argument("--log")
    args = ap.parse_args()
    radkit = os.path.abspath(args.radkit)
    os.makedirs(args.work, exist_ok=True)
    counts, problems, peak = {}, [], {}
    log = open(args.log, "w") if args.log else None
    ran = run_cases(radkit, args.work, args.data, args.cases, args.seed, args.timeout, args.jobs, counts, problems, log,
                    peak=peak)
    print("hostile-option cases: %d run" % ran)
    for (command, outcome), v in sorted(counts.items()):
        print("  %-19s %-17s %d" % (command, outcome, v))
    for command, mb in sorted(peak.items()):
        print("  %-19s peak %.0f MB" % (command, mb))
    for line in problems:
        print("  " + line)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

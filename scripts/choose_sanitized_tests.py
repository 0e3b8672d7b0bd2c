#!/usr/bin/env python3
"""Chooses the tests that the sanitized run (scripts/sanitize.sh) may leave to the ordinary run.

The sanitizers check the code a test executes. A test whose executed code the other sanitized
tests all execute too adds time to the sanitized run but no code for the sanitizers to check.
This script measures that with clang's source-based coverage:

1. builds the tests with coverage counters (-fprofile-instr-generate -fcoverage-mapping, -O1,
   no MPI, no Python module: the configuration of the sanitized build) in BUILD;
2. runs every test alone, as the sanitized run does (BLOCKDEM_TEST_SANITIZED=1), each with a
   profile directory of its own, so that the counters of the `blockdem` processes a test starts
   count for that test;
3. keeps, for each test, the coverage counters (a function's regions) it made non-zero, the
   lines it executed and the branch arms it took in the library (src/blockdem/) and the
   command-line program (apps/cli/);
4. goes through the tests the list leaves out already, then those of at least --min-seconds,
   each longest first, and leaves a test out when every counter, line and arm it reaches is
   reached by another test still in: the tests kept reach all that the tests reach together
   (checked at the end on the merged profiles). Starting from the list keeps it where it still
   holds, rather than following the noise of the timings between siblings of a similar length.

It writes the names left out to tests/sanitize_skip.txt, which scripts/sanitize.sh reads. A test
not named there (a new one, a renamed one) runs under the sanitizers. Run it again when tests or
the code they reach change much; it takes about an hour on the 2-core machine.

Usage: python3 scripts/choose_sanitized_tests.py [--build DIR] [--min-seconds S] [--jobs N]
Standard library only, for any python3.
"""
import argparse
import concurrent.futures as futures
import glob
import json
import os
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
# Tests that never run under the sanitizers (scripts/sanitize.sh says why).
NEVER_SANITIZED = ("Install.", "Docs.", "Python.")


def build(build_dir, jobs):
    flags = "-fprofile-instr-generate -fcoverage-mapping"
    subprocess.run(["cmake", "-S", str(ROOT), "-B", build_dir, "-DCMAKE_CXX_COMPILER=clang++",
                    "-DCMAKE_BUILD_TYPE=RelWithDebInfo", "-DBLOCKDEM_BUILD_BENCH=OFF",
                    "-DBLOCKDEM_PYTHON=OFF", "-DBLOCKDEM_MPI=OFF",
                    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DNDEBUG", f"-DCMAKE_CXX_FLAGS={flags}",
                    "-DCMAKE_EXE_LINKER_FLAGS=-fprofile-instr-generate"],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build_dir, "-j", str(jobs)], check=True,
                   stdout=subprocess.DEVNULL)


def list_tests(build_dir):
    listing = json.loads(subprocess.check_output(
        ["ctest", "--test-dir", build_dir, "--show-only=json-v1"]))
    tests = []
    for index, test in enumerate(listing["tests"]):
        if test["name"].startswith(NEVER_SANITIZED):
            continue
        properties = {p["name"]: p["value"] for p in test.get("properties", [])}
        # A parameterised case without its printed parameter, which can hold addresses.
        name = test["name"].split("  # GetParam() = ")[0]
        tests.append({"index": index, "name": name, "command": test["command"],
                      "environment": properties.get("ENVIRONMENT", []),
                      "directory": properties.get("WORKING_DIRECTORY", build_dir)})
    return tests


def run_test(test, profiles):
    directory = os.path.join(profiles, str(test["index"]))
    os.makedirs(directory, exist_ok=True)
    for old in glob.glob(os.path.join(directory, "*.profraw")):
        os.remove(old)
    env = dict(os.environ)
    for assignment in test["environment"]:
        key, value = assignment.split("=", 1)
        env[key] = value
    env["LLVM_PROFILE_FILE"] = os.path.join(directory, "%p.profraw")
    env["BLOCKDEM_TEST_SANITIZED"] = "1"
    start = time.monotonic()
    try:
        code = subprocess.run(test["command"], cwd=test["directory"], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              timeout=1800).returncode
    except subprocess.TimeoutExpired:
        code = "timeout"
    return {"name": test["name"], "index": test["index"], "code": code,
            "seconds": time.monotonic() - start}


def counters_reached(profdata):
    """{function name: set of counter indices > 0} of one merged profile (text format)."""
    text = subprocess.run(["llvm-profdata", "merge", "-text", "-o", "-", profdata], check=True,
                          capture_output=True, text=True).stdout.split("\n")
    reached = {}
    k = 0
    while k + 6 < len(text):
        if text[k + 1] == "# Func Hash:" and text[k + 3] == "# Num Counters:":
            count = int(text[k + 4])
            values = text[k + 6:k + 6 + count]
            hit = {j for j, v in enumerate(values) if int(v) > 0}
            if hit:
                reached.setdefault(text[k], set()).update(hit)
            k += 6 + count
        else:
            k += 1
    return reached


def lines_and_branches(build_dir, profdata):
    """{(file, line)} executed and {(file, line, block, branch)} taken in the project's code."""
    lcov = subprocess.run(
        ["llvm-cov", "export", "-format=lcov", f"-instr-profile={profdata}",
         os.path.join(build_dir, "blockdem_tests"), "-object", os.path.join(build_dir, "blockdem"),
         str(ROOT / "src" / "blockdem"), str(ROOT / "apps" / "cli")],
        check=True, capture_output=True, text=True).stdout
    reached = set()
    source = ""
    for line in lcov.split("\n"):
        if line.startswith("SF:"):
            source = line[3:]
        elif line.startswith("DA:"):
            number, hits = line[3:].split(",")[:2]
            if int(hits) > 0:
                reached.add((source, int(number)))
        elif line.startswith("BRDA:"):
            number, block, branch, taken = line[5:].split(",")
            # An arm's count is a difference of two counters; at -O1 it can come out negative,
            # which the lcov export prints wrapped to 32 bits (4294967290 for -6): not a count,
            # not an arm reached. (A real count of 2^31 or more, two billion passes of one
            # branch in one test, is taken for such a wrap too.)
            if taken not in ("-", "0") and int(taken) % 2**32 < 2**31:
                reached.add((source, int(number), block, branch))
    return reached


def merge(profiles, index, out):
    raws = glob.glob(os.path.join(profiles, str(index), "*.profraw"))
    if not raws:
        return None
    subprocess.run(["llvm-profdata", "merge", "-sparse", "-o", out] + raws, check=True,
                   stderr=subprocess.DEVNULL)
    return out


def project_functions(build_dir, profdata):
    """Names of the functions defined in src/blockdem/ or apps/cli/ (llvm-cov's export)."""
    export = json.loads(subprocess.check_output(
        ["llvm-cov", "export", "-skip-expansions", "-summary-only=false",
         f"-instr-profile={profdata}", os.path.join(build_dir, "blockdem_tests"),
         "-object", os.path.join(build_dir, "blockdem")]))
    roots = (str(ROOT / "src" / "blockdem") + "/", str(ROOT / "apps" / "cli") + "/")
    names = set()
    for function in export["data"][0]["functions"]:
        if any(f.startswith(roots) for f in function["filenames"]):
            names.add(function["name"])
    return names


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build-coverage"))
    parser.add_argument("--min-seconds", type=float, default=2.0,
                        help="only tests at least this long (coverage build) may be left out")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--out", default=str(ROOT / "tests" / "sanitize_skip.txt"))
    parser.add_argument("--choose-only", action="store_true",
                        help="choose again from the profiles of the last run in --build")
    parser.add_argument("--prefer", default=None,
                        help="a list whose tests are considered first (default: --out as it is)")
    args = parser.parse_args()
    profiles = os.path.join(args.build, "test-profiles")
    record = os.path.join(profiles, "results.json")
    if args.choose_only:
        with open(record) as f:
            results = json.load(f)
    else:
        build(args.build, args.jobs)
        tests = list_tests(args.build)
        print(f"choose_sanitized_tests: running {len(tests)} tests alone", flush=True)
        with futures.ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda t: run_test(t, profiles), tests))
        with open(record, "w") as f:
            json.dump(results, f, indent=1)
    failed = [r["name"] for r in results if r["code"] not in (0, 77)]
    for name in failed:
        print(f"choose_sanitized_tests: failed (kept): {name}", file=sys.stderr)

    def reached(result):
        out = os.path.join(profiles, f"{result['index']}.profdata")
        if not merge(profiles, result["index"], out):
            return {}, set()
        return counters_reached(out), lines_and_branches(args.build, out)
    with futures.ThreadPoolExecutor(args.jobs) as pool:
        per_test = list(pool.map(reached, results))
    everything = os.path.join(profiles, "all.profdata")
    parts = [os.path.join(profiles, f"{r['index']}.profdata") for r in results]
    subprocess.run(["llvm-profdata", "merge", "-sparse", "-o", everything]
                   + [p for p in parts if os.path.exists(p)], check=True)
    functions = project_functions(args.build, everything)

    # counters[i]: the (function, counter) pairs test i reaches in the project's code.
    # with the lines it executes and the branch arms it takes there (llvm-cov's lcov export: a
    # branch's second arm has no counter of its own, its count is the difference of two).
    counters = [{(f, c) for f, hit in r.items() if f in functions for c in hit} | lines
                for r, lines in per_test]
    kept_by = {}
    for reach in counters:
        for counter in reach:
            kept_by[counter] = kept_by.get(counter, 0) + 1
    # The tests the list leaves out already come first (longest first), then the others: a test
    # that shares code with a sibling of about its length stays where it was, so that the list
    # changes where the code or the tests need it, not with the noise of the timings.
    prefer_file = args.prefer or args.out
    preferred = set()
    if os.path.exists(prefer_file):
        with open(prefer_file) as f:
            preferred = {line.strip() for line in f if line.strip() and not line.startswith("#")}
    order = sorted(range(len(results)),
                   key=lambda i: (results[i]["name"] not in preferred, -results[i]["seconds"]))
    left_out = []
    for i in order:
        result = results[i]
        if result["name"] in failed or (result["seconds"] < args.min_seconds
                                        and result["name"] not in preferred):
            continue
        if all(kept_by[c] >= 2 for c in counters[i]):
            for c in counters[i]:
                kept_by[c] -= 1
            left_out.append(result)
    total = sum(r["seconds"] for r in results)
    saved = sum(r["seconds"] for r in left_out)
    with open(args.out, "w") as out:
        out.write("# Tests that scripts/sanitize.sh leaves to the ordinary run: every coverage counter\n"
                  "# (region), line and branch arm of src/blockdem/ and apps/cli/ that one of them reaches,\n"
                  "# a test that runs under the sanitizers reaches too. Written by\n"
                  "# scripts/choose_sanitized_tests.py; one CTest name a line (a parameterised\n"
                  "# case without its printed parameter).\n"
                  f"# {len(left_out)} of {len(results)} tests, {saved:.0f} s of the {total:.0f} s "
                  f"the tests took in the coverage build; {len(kept_by)} counters, lines and arms reached.\n")
        for result in sorted(left_out, key=lambda r: r["name"]):
            out.write(result["name"] + "\n")
    print(f"choose_sanitized_tests: {len(left_out)} tests left out, {saved:.0f} s of {total:.0f} s; "
          f"wrote {args.out}")
    # The check: the kept tests' profiles merged reach the same lines and branch arms as all.
    left_names = {r["name"] for r in left_out}
    kept = os.path.join(profiles, "kept.profdata")
    subprocess.run(["llvm-profdata", "merge", "-sparse", "-o", kept]
                   + [p for r, p in zip(results, parts)
                      if r["name"] not in left_names and os.path.exists(p)], check=True)
    # llvm-profdata keeps one record of a function whose profiles disagree ("functions have
    # mismatched data"), so a merged profile can miss an arm that a test's own profile has: such
    # an arm is named with the kept tests that reach it; one that no kept test reaches fails.
    missing = lines_and_branches(args.build, everything) - lines_and_branches(args.build, kept)
    unreached = 0
    for item in sorted(missing):
        by = [r["name"] for r, (_, lines) in zip(results, per_test)
              if r["name"] not in left_names and item in lines]
        unreached += not by
        print(f"choose_sanitized_tests: check: {item} missing from the kept tests' merged profile;"
              f" reached by {len(by)} kept tests alone ({', '.join(by[:2])}...)")
    print(f"choose_sanitized_tests: check: {len(missing)} lines or branch arms of all the tests' "
          f"merged profile missing from the kept tests', {unreached} reached by no kept test")
    sys.exit(1 if unreached else 0)


if __name__ == "__main__":
    main()

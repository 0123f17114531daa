"""Configured without the shared data, every test that reads it is reported skipped, with its
reason, and none fails: once with PCB_REFERENCE_DIR, PCB_LAS_DATA_DIR, PCB_REAL_DATA_DIR and PCB_PCD_DATA_DIR
naming folders that do not exist, once with them not set (and never in the environment).

    CheckSkipWithoutSharedData.py SOURCE_DIR BUILD_DIR

The project is configured in a scratch folder with BUILD_DIR's options, and nothing is built: the
scratch tree's programs, libraries and plugin are links to BUILD_DIR's, so that each test runs its
real command. The tests that read the data are those whose command or environment names the
missing folders of the first configuration.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

VARIABLES = ("PCB_REFERENCE_DIR", "PCB_LAS_DATA_DIR", "PCB_REAL_DATA_DIR", "PCB_PCD_DATA_DIR")
# The build's options that decide which tests there are, given to the scratch configuration too.
MIRRORED = ("CMAKE_BUILD_TYPE", "CMAKE_CXX_COMPILER", "CMAKE_C_COMPILER", "PCB_WITH_VTK",
            "PCB_WITH_PARAVIEW", "PCB_SANITIZE", "PCB_BUILD_FUZZERS", "VTK_DIR", "ParaView_DIR")


def read_cache(build):
    cache = {}
    with open(os.path.join(build, "CMakeCache.txt")) as lines:
        for line in lines:
            match = re.match(r"^([A-Za-z_0-9]+):[A-Z]+=(.*)$", line.rstrip("\n"))
            if match:
                cache[match.group(1)] = match.group(2)
    return cache


def run(command, cwd=None, check=True):
    """Runs a command without the variables in its environment; its output."""
    environment = {k: v for k, v in os.environ.items() if k not in VARIABLES}
    result = subprocess.run(command, cwd=cwd, env=environment, capture_output=True, text=True)
    if check and result.returncode != 0:
        sys.exit(f"FAILED: {' '.join(command)}\n{result.stdout}{result.stderr}")
    return result.stdout


def configure(source, scratch, cache, folders):
    options = [f"-D{name}={cache[name]}" for name in MIRRORED if cache.get(name)]
    options += [f"-D{name}={folder}" for name, folder in zip(VARIABLES, folders)]
    run([cache["CMAKE_COMMAND"], "-S", source, "-B", scratch, "-G", cache["CMAKE_GENERATOR"]] +
        options)


def link_programs(build, scratch, cache):
    """Links every program and library of the build into the scratch tree, beside the files
    the configuration wrote there."""
    for folder in {cache.get("CMAKE_INSTALL_BINDIR") or "bin",
                   cache.get("CMAKE_INSTALL_LIBDIR") or "lib"}:
        for root, _, files in os.walk(os.path.join(build, folder)):
            relative = os.path.relpath(root, build)
            os.makedirs(os.path.join(scratch, relative), exist_ok=True)
            for name in files:
                link = os.path.join(scratch, relative, name)
                if not os.path.lexists(link):
                    os.symlink(os.path.join(root, name), link)


def data_tests(scratch, cache, folders):
    """The tests whose command or environment names one of the folders, and all the tests."""
    listing = json.loads(run([cache["CMAKE_CTEST_COMMAND"], "--show-only=json-v1"], cwd=scratch))
    names = []
    for test in listing["tests"]:
        words = list(test.get("command", []))
        for prop in test.get("properties", []):
            if prop["name"] == "ENVIRONMENT":
                words += prop["value"]
        if any(folder in word for folder in folders for word in words):
            names.append(test["name"])
    return names, {test["name"] for test in listing["tests"]}


def check_skipped(scratch, cache, names):
    """Runs the tests and returns what is wrong: each must be skipped by its SKIP_RETURN_CODE,
    its output saying why (a line "skipped: ..." naming the variable to set)."""
    report = os.path.join(scratch, "results.xml")
    pattern = "^(" + "|".join(re.escape(name) for name in names) + ")$"
    run([cache["CMAKE_CTEST_COMMAND"], "-R", pattern, "--output-junit", report], cwd=scratch,
        check=False)
    results = {case.get("name"): case for case in ElementTree.parse(report).getroot()}
    problems = []
    for name in names:
        case = results.get(name)
        if case is None:
            problems.append(f"{name}: not run")
            continue
        skipped = case.find("skipped")
        output = case.findtext("system-out") or ""
        if (case.get("status") != "notrun" or skipped is None or
                not skipped.get("message", "").startswith("SKIP_RETURN_CODE")):
            problems.append(f"{name}: {case.get('status')}, not skipped:\n{output}")
        elif not re.search(r"(?i)skipped: .*(" + "|".join(VARIABLES) + ")", output):
            problems.append(f"{name}: skipped without saying why:\n{output}")
        else:
            print(f"ok: {name}: {output.strip().splitlines()[-1]}")
    return problems


def main():
    source, build = (os.path.abspath(path) for path in sys.argv[1:3])
    cache = read_cache(build)
    scratch = tempfile.mkdtemp(prefix="pcb-no-shared-data.")
    try:
        missing = [os.path.join(scratch, "missing-" + name) for name in VARIABLES]
        configure(source, scratch, cache, missing)
        link_programs(build, scratch, cache)
        names, _ = data_tests(scratch, cache, missing)
        if not names:
            sys.exit("FAILED: no test names the shared data folders")
        print("the tests that read the shared data:", " ".join(names))
        problems = check_skipped(scratch, cache, names)
        # Not set at all: the same tests, none left out or disabled, each skipped.
        configure(source, scratch, cache, [""] * len(VARIABLES))
        _, all_names = data_tests(scratch, cache, [])
        problems += [f"{name}: no such test when the data is not set" for name in names
                     if name not in all_names]
        present = [name for name in names if name in all_names]
        problems += check_skipped(scratch, cache, present)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    for problem in problems:
        print("FAILED:", problem)
    if problems:
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

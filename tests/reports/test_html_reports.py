"""The HTML reports, end to end: each `gradem` command that writes a report is run on
small real inputs, its report.html is opened in headless Chromium, and the test asserts that the
expected number of figures is there and rendered (an <svg> with a box and drawn paths, counted by
the page's own check into <html data-figures-rendered>), that the page logged nothing to the
console (no script errors, no blocked external resource: the network is switched off), that the
screenshot is not blank, and that the REPRESENTATIVE banner is present exactly when the inputs are
the bundled representative cube exports. The `failures` case checks the optional-report contract
without a browser: missing python3 or matplotlib, bad input, no half-written or stale report.

    /usr/bin/python3 test_html_reports.py CASE --gradem BUILD/app/gradem --source SOURCE_DIR

CASE: checker | lab | lab_tension | compress | calibrate | study | failures. Exit 0 pass, 1 fail, 77 skipped (no
chromium; with GRADEM_REQUIRE_BROWSER=1 a missing browser is a failure instead).
"""

import argparse
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

SKIP = 77
EXPECTED_FIGURES = {"lab": 3, "lab_tension": 2, "compress": 4, "calibrate": 6}
# figures of the study report per study kind (reports/html/study_report.py)
STUDY_FIGURES = {"gradation_effect": 2, "sensitivity": 1, "resolution": 1, "fines_truncation": 2, "model_form": 3}
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update", "--disable-sync", "--hide-scrollbars",
                  "--host-resolver-rules=MAP * ~NOTFOUND", "--enable-logging=stderr", "--v=0"]


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def find_browser():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


def run(cmd, env=None, timeout=300):
    env = dict(os.environ, **(env or {}))
    return subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)


# ----------------------------------------------------------------------------- browser checks

def open_in_browser(browser, page, work, height=5000):
    """(dom text, console lines, screenshot path) of `page` in headless Chromium."""
    url = "file://" + os.path.abspath(page)
    profile = tempfile.mkdtemp(dir=work, prefix="profile-")
    dom = run([browser, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", "--dump-dom", url], timeout=120)
    check(dom.returncode == 0, f"chromium --dump-dom failed ({dom.returncode}): {dom.stderr[-800:]}")
    shot = os.path.join(work, os.path.basename(page) + ".png")
    profile = tempfile.mkdtemp(dir=work, prefix="profile-")
    s = run([browser, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", f"--window-size=1200,{height}", f"--screenshot={shot}", url],
            timeout=120)
    check(s.returncode == 0 and os.path.isfile(shot), f"chromium --screenshot failed ({s.returncode}): {s.stderr[-800:]}")
    console = [line for line in (dom.stderr + s.stderr).splitlines() if ":CONSOLE" in line]
    return dom.stdout, console, shot


def screenshot_stats(png):
    """(fraction of pixels that are not the page background, standard deviation of the grey level)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import numpy as np
    pixels = mpimg.imread(png)[..., :3]
    grey = pixels.mean(axis=2)
    background = np.median(grey)
    return float(np.mean(np.abs(grey - background) > 0.08)), float(grey.std())


def check_page_in_browser(browser, page, work, figures, banner, height=5000):
    dom, console, shot = open_in_browser(browser, page, work, height)
    check(not console, f"{page}: the browser console is not empty:\n  " + "\n  ".join(console[:10]))
    declared = re.search(r'data-figures="(\d+)"', dom)
    rendered = re.search(r'data-figures-rendered="(\d+)"', dom)
    check(declared and rendered, f"{page}: the page's figure check did not run (no data-figures attributes in the DOM)")
    check(int(declared.group(1)) == figures, f"{page}: {declared.group(1)} figures, expected {figures}")
    check(int(rendered.group(1)) == figures, f"{page}: {rendered.group(1)} of {figures} figures rendered")
    check(dom.count("<svg") == figures, f"{page}: {dom.count('<svg')} <svg> elements, expected {figures}")
    has_banner = "REPRESENTATIVE DATA, NOT MEASUREMENTS" in dom
    check(has_banner == banner, f"{page}: REPRESENTATIVE banner {'missing' if banner else 'present but the data are not representative'}")
    ink, spread = screenshot_stats(shot)
    check(ink > 0.03 and spread > 0.05, f"{page}: the screenshot looks blank (ink {ink:.3f}, grey std {spread:.3f}): {shot}")
    return shot


def check_self_contained(page):
    text = open(page, encoding="utf-8").read()
    check(not re.search(r'(src|href)\s*=\s*"(https?:)?//', text), f"{page}: refers to an external resource")
    check("<link" not in text and "@import" not in text and "url(http" not in text, f"{page}: loads external CSS or fonts")


# ----------------------------------------------------------------------------- cases

def case_checker(args, browser, work):
    """The browser checks themselves can fail: a console error, a blank page and a page whose
    figure is missing are each caught."""
    pages = {
        "console": '<!DOCTYPE html><html><body><p>text</p><script>console.error("boom")</script></body></html>',
        "blank": "<!DOCTYPE html><html><body></body></html>",
    }
    for name, text in pages.items():
        path = os.path.join(work, name + ".html")
        with open(path, "w") as f:
            f.write(text)
        dom, console, shot = open_in_browser(browser, path, work, height=600)
        if name == "console":
            check(any("boom" in line for line in console), "a console.error was not seen in the browser log")
        else:
            ink, spread = screenshot_stats(shot)
            check(ink < 0.01 and spread < 0.02, f"a blank page was not recognised as blank (ink {ink:.3f}, std {spread:.3f})")
    # A real report with one figure removed: the count check fails.
    lab = make_lab(args, work)
    text = open(os.path.join(lab, "report.html"), encoding="utf-8").read()
    start = text.index('<figure class="report-figure"')
    end = text.index("</figure>", start) + len("</figure>")
    broken = os.path.join(work, "one-figure-less.html")
    with open(broken, "w", encoding="utf-8") as f:
        f.write(text[:start] + text[end:])
    try:
        check_page_in_browser(browser, broken, work, EXPECTED_FIGURES["lab"], banner=True)
    except Failure as e:
        check("figures" in str(e), f"a missing figure was reported as something else: {e}")
    else:
        raise Failure("a report with a figure removed passed the figure check")


def make_lab(args, work):
    out = os.path.join(work, "lab")
    r = run([args.gradem, "lab", os.path.join(args.source, "lab_data/datasets/study"), "--out", out])
    check(r.returncode == 0, f"gradem lab failed ({r.returncode}): {r.stderr[-800:]}")
    page = os.path.join(out, "report.html")
    check(f"report: {page}" in r.stdout, f"gradem lab did not announce its report: {r.stdout[-300:]} {r.stderr[-500:]}")
    check(os.path.isfile(page), f"no {page}")
    return out


def case_lab(args, browser, work):
    out = make_lab(args, work)
    page = os.path.join(out, "report.html")
    check_self_contained(page)
    return check_page_in_browser(browser, page, work, EXPECTED_FIGURES["lab"], banner=True)


def case_lab_tension(args, browser, work):
    """Tension specimens alone (the generated two-sand fixture dataset): the gradation panel and
    the tensile-strength figure, no cube sections, the specimens' table."""
    out = os.path.join(work, "lab_tension")
    r = run([args.gradem, "lab", os.path.join(args.source, "tests/lab_data/fixtures/tension_dataset"), "--out", out])
    check(r.returncode == 0, f"gradem lab failed ({r.returncode}): {r.stderr[-800:]}")
    page = os.path.join(out, "report.html")
    check(os.path.isfile(page), f"no {page}")
    text = open(page, encoding="utf-8").read()
    check("Tensile strength of the specimens, per sand" in text, f"{page}: no tensile-strength figure")
    check("Cube compression curves" not in text, f"{page}: cube sections without cubes")
    check("A-F1.csv" in text and "direct tensile strength" in text, f"{page}: no tension specimens' table or statistics")
    check_self_contained(page)
    return check_page_in_browser(browser, page, work, EXPECTED_FIGURES["lab_tension"], banner=True)


def make_calibration(args, work):
    """A calibration with the closed-form stand-in model (seconds); returns (output folder, stdout)."""
    lab = make_lab(args, work)
    config = os.path.join(work, "analytic.toml")
    out = os.path.join(work, "calibration")
    with open(config, "w") as f:
        f.write(f'''# a calibration of both sands with the closed-form stand-in model (seconds, no DEM)
[calibration]
base = "{args.source}/experiments/configs/calibration_cube.toml"
model = "analytic"
mode = "joint"
sand_seeds = {{ "Van Buren" = [1, 2, 3] }}
[targets]
lab_results = "{lab}/lab_results.json"
[solver]
max_runs = 40
[scale_up]
edge_mm = 3.5
seeds = [21]
[validation]
seeds = [31]
[output]
dir = "{out}"
''')
    r = run([args.gradem, "calibrate", config])
    check(r.returncode == 0, f"gradem calibrate failed ({r.returncode}): {r.stderr[-800:]}")
    return out, r.stdout


def case_calibrate(args, browser, work):
    out, stdout = make_calibration(args, work)
    page = os.path.join(out, "report.html")
    check(stdout.rstrip().endswith(f"report: {page}"), f"gradem calibrate does not end with its report's path: {stdout[-300:]}")
    text = open(page, encoding="utf-8").read()
    check("validation specimens, which the fit never saw" in text and "on the scale-up specimens" in text
          and "3.5 mm cubes, packing seeds 21" in text, f"{page}: no validation errors figure or scale-up caption")
    check("pre-blended: 1, 2; Van Buren: 1, 2, 3" in text, f"{page}: the run table does not give each sand's own packing seeds")
    # The shape index figure's caption gives each sand's D as summary.json has it: the lab's, then each
    # specimen set's (fitted, scale-up, validation).
    summary = json.load(open(os.path.join(out, "summary.json"), encoding="utf-8"))
    rows = summary["stages"][0]["shape_index_d"]
    check({r["role"] for r in rows} == {"fitted", "scale-up", "validation"}, f"{out}/summary.json: shape index roles {rows}")
    for sand in ("pre-blended", "Van Buren"):
        mine = [r for r in rows if r["sand"] == sand]
        want = f"{sand}: lab {mine[0]['lab']:.2f}, " + ", ".join(f"{r['role']} {r['simulated']:.2f}" for r in mine)
        found = re.search(re.escape(sand) + r": lab [^;]*", text)
        check(want in text, f"{page}: the shape index caption does not say '{want}' (it says '{found and found.group(0)}')")
    check_self_contained(page)
    return check_page_in_browser(browser, page, work, EXPECTED_FIGURES["calibrate"], banner=True)


def case_study(args, browser, work):
    """Every study kind on the closed-form stand-in (the stand-in ignores the specimen, so the
    edge and fines sweeps run in milliseconds): `gradem study` ends with its report's path, and
    each page has its kind's figures, rendered, the study's verdict and the banner (the lab data
    the calibration was fitted to are the representative ones)."""
    calibration, _ = make_calibration(args, work)
    # model_form compares calibrations: the same one under a second name will do for the page.
    second = os.path.join(work, "calibration-copy")
    os.makedirs(second)
    shutil.copy(os.path.join(calibration, "summary.json"), second)
    keys = {"resolution": "edges_mm = [2.5, 3.5, 5.0]", "fines_truncation": "min_diameters_mm = [0.106, 0.149, 0.25]"}
    shot = None
    for kind, figures in STUDY_FIGURES.items():
        out = os.path.join(work, f"study-{kind}")
        config = os.path.join(work, f"{kind}.toml")
        with open(config, "w") as f:
            if kind == "model_form":
                f.write(f'[study]\nkind = "model_form"\ncalibrations = ["{calibration}/summary.json", "{second}/summary.json"]\n')
            else:
                f.write(f'[study]\nkind = "{kind}"\ncalibration = "{calibration}/summary.json"\nseeds = [11, 12, 13]\n'
                        f'{keys.get(kind, "")}\n[run]\nworkers = 2\n')
            f.write(f'[output]\ndir = "{out}"\n')
        r = run([args.gradem, "study", config])
        check(r.returncode == 0, f"gradem study ({kind}) failed ({r.returncode}): {r.stderr[-800:]}")
        page = os.path.join(out, "report.html")
        check(r.stdout.rstrip().endswith(f"report: {page}"), f"gradem study ({kind}) does not end with its report's path: {r.stdout[-300:]}")
        check_self_contained(page)
        verdict = json.load(open(os.path.join(out, "study.json"), encoding="utf-8"))["verdict"]
        text = open(page, encoding="utf-8").read()
        check(verdict and all(html.escape(v.replace(" -> ", " → ")) in text for v in verdict),
              f"{page}: the study's verdict is not on the page")
        if kind == "model_form":  # the calibration has [validation]: its errors there, beside the fitted ones
            check("white diamonds: on its validation specimens" in text, f"{page}: no validation errors in the target figure")
        # The study pages are shorter than the others: a 2000-px window keeps the blank check fair.
        this = check_page_in_browser(browser, page, work, figures, banner=True, height=2000)
        if kind == "gradation_effect":
            shot = os.path.join(work, "study-gradation_effect.png")
            shutil.copy(this, shot)
    # A failed run (the stand-in never fails, so one is marked failed in a copy of study.json):
    # `gradem report study` lists it with the runner's reason, and the failed card counts it.
    failed = os.path.join(work, "study-with-a-failed-run")
    shutil.copytree(os.path.join(work, "study-gradation_effect"), failed)
    study_path = os.path.join(failed, "study.json")
    study = json.load(open(study_path, encoding="utf-8"))
    study["cases"][0]["sands"][1]["runs"][0].update(status="failed", reason="timed out after 600 s")
    study["runs"]["failed"] = 1
    json.dump(study, open(study_path, "w", encoding="utf-8"))
    r = run([args.gradem, "report", "study", failed])
    check(r.returncode == 0, f"gradem report study failed ({r.returncode}): {r.stderr[-500:]}")
    text = open(os.path.join(failed, "report.html"), encoding="utf-8").read()
    check(re.search(r'<tr class="bad">(<td[^>]*>[^<]*</td>){3}<td class="text">failed</td><td class="text">timed out after 600 s</td>', text),
          f"{failed}/report.html: the failed run and its reason are not listed")
    return shot


def case_compress(args, browser, work):
    """The outputs of a real (small) `gradem compress` run are committed as a fixture: a cube test
    takes minutes. The report is made by `gradem report compress` from a copy."""
    out = os.path.join(work, "compress")
    shutil.copytree(os.path.join(args.source, "tests/reports/fixtures/compress"), out)
    r = run([args.gradem, "report", "compress", out])
    check(r.returncode == 0, f"gradem report compress failed ({r.returncode}): {r.stderr[-800:]}")
    page = os.path.join(out, "report.html")
    check_self_contained(page)
    return check_page_in_browser(browser, page, work, EXPECTED_FIGURES["compress"], banner=False)


def leftovers(folder):
    return sorted(n for n in os.listdir(folder) if n.startswith("report.html"))


def case_failures(args, browser, work):
    lab = make_lab(args, work)
    check(leftovers(lab) == ["report.html"], f"unexpected files: {leftovers(lab)}")

    # Edge input: one export file (no sieve analysis, no standard deviation, not representative):
    # the report is still made, with all its figures and without the banner.
    files = os.path.join(work, "lab-files")
    r = run([args.gradem, "lab", os.path.join(args.source, "tests/lab_data/fixtures/plain.csv"), "--out", files])
    page = os.path.join(files, "report.html")
    check(r.returncode == 0 and os.path.isfile(page), f"no report for a single export file: {r.stderr[-600:]}")
    text = open(page, encoding="utf-8").read()
    check(text.count("<svg") == EXPECTED_FIGURES["lab"], f"{page}: {text.count('<svg')} figures")
    check("REPRESENTATIVE DATA" not in text, f"{page}: banner on data that are not representative")

    # No python3: the command still succeeds with its other outputs, warns, and removes the
    # stale report of the earlier run (it no longer belongs to the files next to it).
    r = run([args.gradem, "lab", os.path.join(args.source, "lab_data/datasets/study"), "--out", lab],
            env={"GRADEM_PYTHON": os.path.join(work, "no-such-python3")})
    check(r.returncode == 0, f"gradem lab failed without python3 ({r.returncode}): {r.stderr[-500:]}")
    check("no-such-python3 not found" in r.stderr and "apt-get install python3-matplotlib" in r.stderr,
          f"no clear warning without python3: {r.stderr[-500:]}")
    check(leftovers(lab) == [], f"report files left without python3: {leftovers(lab)}")
    check(os.path.isfile(os.path.join(lab, "lab_results.json")), "lab_results.json missing")

    # No matplotlib: an interpreter on which `import matplotlib` fails.
    fake = os.path.join(work, "python-without-matplotlib")
    blocker = os.path.join(work, "blocker")
    os.makedirs(os.path.join(blocker, "matplotlib"))
    with open(os.path.join(blocker, "matplotlib", "__init__.py"), "w") as f:
        f.write('raise ImportError("simulated: no matplotlib", name="matplotlib")\n')
    with open(fake, "w") as f:
        f.write(f'#!/bin/sh\n# drops the isolation flags so PYTHONPATH can shadow matplotlib\nshift 3\n'
                f'PYTHONPATH={blocker} exec /usr/bin/python3 "$@"\n')
    os.chmod(fake, 0o755)
    r = run([args.gradem, "report", "lab", lab], env={"GRADEM_PYTHON": fake})
    check(r.returncode == 3, f"gradem report without matplotlib: exit {r.returncode}, expected 3")
    check("cannot import matplotlib" in r.stderr and "apt-get install python3-matplotlib" in r.stderr,
          f"no clear message without matplotlib: {r.stderr[-500:]}")
    check(leftovers(lab) == [], f"report files left without matplotlib: {leftovers(lab)}")

    # A generator killed half-way through writing: the half-written page is not left behind.
    killed = os.path.join(work, "python-killed-midway")
    with open(killed, "w") as f:
        f.write('#!/bin/sh\n# args: -B -E -s make_report.py KIND OUT_DIR TEMP\nprintf "<!DOCTYPE html><html><body>half" > "$7"\n'
                'kill -9 $$\n')
    os.chmod(killed, 0o755)
    r = run([args.gradem, "report", "lab", lab], env={"GRADEM_PYTHON": killed})
    check(r.returncode == 3 and "exit 137" in r.stderr, f"killed generator: exit {r.returncode}: {r.stderr[-400:]}")
    check(leftovers(lab) == [], f"a half-written report was left: {leftovers(lab)}")

    # Bad input: a missing file and a garbled number are named (file, line), exit 1, no report.
    r = run([args.gradem, "report", "calibrate", lab])
    check(r.returncode == 1 and "summary.json: no such file" in r.stderr, f"missing summary.json: {r.returncode} {r.stderr[-400:]}")
    curves = os.path.join(lab, "curves.csv")
    lines = open(curves, encoding="utf-8").read().splitlines()
    header = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    lines[header + 3] = lines[header + 3].rsplit(",", 1)[0] + ",12.x"
    with open(curves, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    r = run([args.gradem, "report", "lab", lab])
    check(r.returncode == 1 and f"curves.csv:{header + 4}: column stress_mpa = '12.x': expected a number" in r.stderr,
          f"garbled curves.csv: exit {r.returncode}: {r.stderr[-400:]}")
    check(leftovers(lab) == [], f"report files left after bad input: {leftovers(lab)}")
    r = run([args.gradem, "report", "nonsense", lab])
    check(r.returncode == 2 and "expected one of lab|compress|calibrate|study" in r.stderr, f"bad kind: {r.returncode} {r.stderr[-300:]}")


CASES = {"checker": case_checker, "lab": case_lab, "lab_tension": case_lab_tension, "compress": case_compress,
         "calibrate": case_calibrate, "study": case_study, "failures": case_failures}
NEEDS_BROWSER = {"checker", "lab", "lab_tension", "compress", "calibrate", "study"}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--gradem", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--keep", help="copy the screenshot here (for reports/README.md)")
    args = parser.parse_args()
    browser = find_browser()
    if args.case in NEEDS_BROWSER and browser is None:
        message = ("no chromium found: the browser test of the HTML reports needs it "
                   "(apt-get install chromium, or run scripts/setup.sh)")
        if os.environ.get("GRADEM_REQUIRE_BROWSER") == "1":
            print(f"FAIL: {message}; GRADEM_REQUIRE_BROWSER=1", file=sys.stderr)
            return 1
        print(f"SKIP: {message}", file=sys.stderr)
        return SKIP
    work = tempfile.mkdtemp(prefix=f"gradem-report-test-{args.case}-")
    try:
        shot = CASES[args.case](args, browser, work)
        if args.keep and shot:
            shutil.copy(shot, args.keep)
        print(f"{args.case}: ok")
        return 0
    except Failure as e:
        print(f"FAIL ({args.case}): {e}", file=sys.stderr)
        return 1
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())

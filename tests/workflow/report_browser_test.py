#!/usr/bin/python3
"""The study report opens in a real browser: Debian's chromium, headless.

A tiny priced DeliBot study (so the report has the schedule and trajectory
figures) runs locally; chromium loads report.html from disk and dumps the
DOM after the page's load event: the page's own script has counted the
images the browser decoded (data-images-decoded="N/M"), and every image
must have decoded. A screenshot is written too and must not be blank; its
path is printed for a person to look at. Skips when chromium is absent.
Usage: report_browser_test.py PATH_TO_RCBENCH [SCREENSHOT.png]
"""
import os
import re
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_test_support as sts  # noqa: E402


def chromium():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    sts.skip("chromium not installed (apt-get install chromium; not needed by CI)")


def browser(binary, work, *args):
    # --no-sandbox: the tests run as root in CI containers, where chromium's sandbox cannot start.
    cmd = [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
           f"--user-data-dir={os.path.join(work, 'chromium-profile')}", "--virtual-time-budget=5000", *args]
    return sts.run(cmd, cwd=work, timeout=120)


def main():
    rcbench = sts.rcbench_from_argv()
    sts.require_engine()
    binary = chromium()
    checks = sts.Checks()
    work = sts.scratch("rc_report_browser_")
    config = sts.tiny_study(work, rcbench, name="browser", grid={"particles": [300, 600]}, records=60,
                            max_records=50, pricing=True)
    result = sts.run(sts.snakemake_command(config, cores=2), cwd=work)
    report = os.path.join(work, "browser", "report.html")
    if not checks.check(result.returncode == 0 and os.path.exists(report), "the study ran and wrote its report"):
        print(result.stdout[-4000:])
        checks.exit()
    with open(report) as f:
        text = f.read()
    checks.check(not re.search(r"(src|href)=['\"](?!data:)[a-z]+:", text) and "<link" not in text,
                 "the report refers to nothing outside itself")
    images = len(re.findall(r"<img ", text))
    checks.check(images >= 2, f"the report has {images} embedded figures (schedule and trajectory at least)")

    dom = browser(binary, work, "--dump-dom", f"file://{report}")
    m = re.search(r'data-images-decoded="(\d+)/(\d+)"', dom.stdout)
    checks.check(m is not None, "chromium ran the page's load script (data-images-decoded present)")
    if m:
        checks.check(m.group(1) == m.group(2) == str(images),
                     f"chromium decoded {m.group(1)} of {m.group(2)} images (the page has {images})")
    screenshot = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(work, "report.png")
    browser(binary, work, f"--screenshot={screenshot}", "--window-size=1280,2400", f"file://{report}")
    if checks.check(os.path.exists(screenshot), f"screenshot written: {screenshot}"):
        from PIL import Image
        pixels = Image.open(screenshot).convert("L")
        lo, hi = pixels.getextrema()
        checks.check(hi - lo > 100, f"the screenshot is not blank (grey levels {lo}-{hi})")
    if checks.failures == 0 and len(sys.argv) <= 2:
        shutil.rmtree(work)
    checks.exit()


if __name__ == "__main__":
    main()

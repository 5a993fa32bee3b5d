#!/usr/bin/env python3
"""The validation report: runs each case of report/cases/, compares it with its published or
analytic reference, and writes an HTML page and its Markdown twin with the plots.

    report/make_report.py [--moreau build/moreau] [--out docs/report] [--fast] [--only NAME ...]
                          [--readme README.md]

`make report` writes docs/report/ and the summary table in README.md (between its "report
summary" markers); `--fast` is the subset `make test` runs (smaller meshes and shorter runs, with
the tolerances that suit them). With `--only`, the named cases are run again and the other cases'
sections are kept from the last run (results.json in the output directory; each section says
which commit computed it). Exits with 1 when a check fails.
"""
import argparse
import dataclasses
import datetime
import html
import json
import pathlib
import platform
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from cases import CASES  # noqa: E402
from report_case import ROOT, CaseResult, Check  # noqa: E402


def number(x):
    return f"{x:.5g}" if x != 0 else "0"


def provenance(fast):
    try:
        commit = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"], capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")),
               platform.processor())
    return (f"moreau {commit}, {datetime.date.today().isoformat()}, {cpu}, one thread"
            + (" — fast subset (smaller meshes, shorter runs)" if fast else ""))


def summary_table(results, link_prefix=""):
    """One row per case: its checks passed and its wall time, linking to its section."""
    lines = ["| case | checks passed | wall time (s) |", "|---|---|---|"]
    for r in results:
        lines.append(f"| [{r.title}]({link_prefix}#{anchor(r.title)}) | {sum(c.passed for c in r.checks)} of "
                     f"{len(r.checks)}{'' if r.passed else ' — **FAILED**'} | {r.wall_s:.1f} |")
    return lines


def update_readme(readme, results, header):
    """Replaces the table between README's report-summary markers."""
    begin, end = "<!-- report summary: written by make report -->", "<!-- end of report summary -->"
    text = readme.read_text()
    if begin not in text or end not in text:
        raise SystemExit(f"{readme}: no report-summary markers to write the table between")
    table = "\n".join([header, ""] + summary_table(results, "docs/report/report.md"))
    readme.write_text(text[:text.index(begin) + len(begin)] + "\n" + table + "\n" + text[text.index(end):])


def cell(text):
    """Text for a Markdown table cell: a | would end the cell."""
    return str(text).replace("|", "\\|")


def markdown(results, header):
    lines = ["# Validation report", "", header, "",
             "Regenerate with `make report`; every figure below was computed by that run.", ""]
    lines += summary_table(results)
    for r in results:
        lines += ["", f"## {r.title}", "", f"Reference: {r.reference}.", "", f"Run: `moreau run {r.scene}`", "",
                  f"Computed by {r.provenance}.", "",
                  "| quantity | moreau | reference | error | tolerance | result | tolerance allows for |",
                  "|---|---|---|---|---|---|---|"]
        for c in r.checks:
            unit = f" {c.unit}" if c.unit else ""
            reference, tolerance = (f"≤ {number(c.reference)}{unit}", "–") if c.is_bound else \
                (f"{number(c.reference)}{unit}", number(c.tolerance))
            lines.append(f"| {cell(c.quantity)} | {number(c.value)}{unit} | {reference} | "
                         f"{'–' if c.is_bound else number(c.error)} | {tolerance} | {'pass' if c.passed else '**FAIL**'} "
                         f"| {cell(c.why)} |")
        lines += [""] + r.notes + ([""] if r.notes else []) + [f"![{r.title}]({p})" for p in r.plots]
    return "\n".join(lines) + "\n"


def anchor(title):
    return "".join(ch for ch in title.lower().replace(" ", "-") if ch.isalnum() or ch == "-")


def page(results, header):
    e = html.escape
    rows = "".join(
        f"<tr><td><a href='#{anchor(r.title)}'>{e(r.title)}</a></td><td>{sum(c.passed for c in r.checks)} of "
        f"{len(r.checks)}</td><td class='{'pass' if r.passed else 'fail'}'>{'pass' if r.passed else 'FAIL'}</td>"
        f"<td>{r.wall_s:.1f}</td></tr>" for r in results)
    sections = ""
    for r in results:
        checks = "".join(
            f"<tr><td>{e(c.quantity)}</td><td>{number(c.value)} {e(c.unit)}</td>"
            f"<td>{'≤ ' if c.is_bound else ''}{number(c.reference)} {e(c.unit)}</td>"
            f"<td>{'–' if c.is_bound else number(c.error)}</td><td>{'–' if c.is_bound else number(c.tolerance)}</td>"
            f"<td class='{'pass' if c.passed else 'fail'}'>{'pass' if c.passed else 'FAIL'}</td><td>{e(c.why)}</td></tr>"
            for c in r.checks)
        figures = "".join(f"<p>{e(n)}</p>" for n in r.notes)
        figures += "".join(f"<img src='{e(p)}' alt='{e(r.title)}'>" for p in r.plots)
        sections += (f"<section id='{anchor(r.title)}'><h2>{e(r.title)}</h2><p>Reference: {e(r.reference)}.</p>"
                     f"<p>Run: <code>moreau run {e(r.scene)}</code> ({r.wall_s:.1f} s); computed by "
                     f"{e(r.provenance)}.</p>"
                     "<table><tr><th>quantity</th><th>moreau</th><th>reference</th><th>error</th><th>tolerance</th>"
                     f"<th>result</th><th>tolerance allows for</th></tr>{checks}</table>{figures}</section>")
    return f"""<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>moreau validation report</title>
<style>
body {{ font: 15px/1.5 system-ui, sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #222; }}
table {{ border-collapse: collapse; margin: 0.8em 0; }} td, th {{ border: 1px solid #ccc; padding: 3px 8px; text-align: left; }}
th {{ background: #f2f2f2; }} .pass {{ color: #18794e; font-weight: 600; }} .fail {{ color: #c62828; font-weight: 700; }}
img {{ max-width: 100%; display: block; margin: 0.5em 0; }} code {{ background: #f4f4f4; padding: 1px 4px; }}
</style></head><body>
<h1>Validation report</h1><p>{e(header)}</p>
<p>Regenerate with <code>make report</code>; every figure below was computed by that run.</p>
<table><tr><th>case</th><th>checks passed</th><th>result</th><th>wall time (s)</th></tr>{rows}</table>
{sections}
</body></html>
"""


def load_results(path):
    """The cases of an earlier run, {module name: CaseResult}, from its results.json (none if absent)."""
    if not path.exists():
        return {}
    saved = json.loads(path.read_text())
    return {name: CaseResult(**{**fields, "checks": [Check(**c) for c in fields["checks"]]})
            for name, fields in saved.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--moreau", default=str(ROOT / "build" / "moreau"))
    parser.add_argument("--out", default=str(ROOT / "docs" / "report"))
    parser.add_argument("--fast", action="store_true", help="the subset make test runs")
    parser.add_argument("--only", nargs="*", help="case modules to run (e.g. ghia_cavity)")
    parser.add_argument("--readme", help="write the summary table into this README's report-summary markers")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    known = [c.__name__.split(".")[-1] for c in CASES]
    unknown = sorted(set(args.only or []) - set(known))
    if unknown:
        print(f"make_report.py: --only: no case named {', '.join(unknown)} in report/cases/__init__.py "
              f"(the cases are {', '.join(known)})", file=sys.stderr)
        return 2
    cases = [c for c in CASES if not args.only or c.__name__.split(".")[-1] in args.only]
    header = provenance(args.fast)
    # A partial run of the whole report keeps the other cases' last results.
    kept = load_results(out / "results.json") if args.only and not args.fast else {}
    by_name = {}
    with tempfile.TemporaryDirectory(prefix="moreau-report-") as work:
        for case in cases:
            name = case.__name__.split(".")[-1]
            case_work = pathlib.Path(work) / name
            case_work.mkdir()
            result = case.run(args.moreau, case_work, out, args.fast)
            result.provenance = header
            by_name[name] = result
            failed = [c.quantity for c in result.checks if not c.passed]
            print(f"{name}: {'pass' if not failed else 'FAIL (' + ', '.join(failed) + ')'} in {result.wall_s:.1f} s",
                  flush=True)
    for name, result in kept.items():
        by_name.setdefault(name, result)
    names = [c.__name__.split(".")[-1] for c in CASES if c.__name__.split(".")[-1] in by_name]
    results = [by_name[n] for n in names]
    if kept:
        header = "cases computed by different runs: each section says which"
    (out / "results.json").write_text(json.dumps({n: dataclasses.asdict(by_name[n]) for n in names}, indent=1,
                                                 ensure_ascii=False))
    (out / "index.html").write_text(page(results, header))
    (out / "report.md").write_text(markdown(results, header))
    if args.readme:
        update_readme(pathlib.Path(args.readme), results, header)
    print(f"report written to {out / 'index.html'} and {out / 'report.md'}")
    ran = [c.__name__.split(".")[-1] for c in cases]
    return 0 if all(by_name[n].passed for n in ran) else 1


if __name__ == "__main__":
    sys.exit(main())

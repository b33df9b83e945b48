#!/usr/bin/env python3
"""score.py -- scoring of `rtb diagnose` reports against refgen truth, for
tests/refgen/acceptance.sh.

  score.py row CASE TRUTH_JSON REPORT_JSON WALL_S CPU_S STATUS >> results.jsonl
  score.py table results.jsonl

Verdict rules (issue #10):
  plain (effect none)          correct iff cause is "none" and no cause is listed
                               (also under a rig convention: preload, compression_positive, colored_noise)
  single vocabulary word       correct iff cause (the first name) is the word
                               (both clearance forms -> "backlash")
  new word                     the same, counted with the combined cases
  combination                  correct iff every expected word is named
  out of vocabulary (hum, drift, clipping, spikes, zero_drift) correct iff cause is "unexplained"
A named word that is not expected is a wrong name ("none" and
"unexplained" never are).
"""
import json
import sys

NEW_WORDS = {"slack", "relaxation_spectrum", "friction_asymmetry"}
NOT_NAMES = {"none", "unexplained"}


def named_words(report):
    """Every cause the report names: causes[].name when present, else cause."""
    if isinstance(report.get("causes"), list):
        words = [c.get("name", "") for c in report["causes"] if isinstance(c, dict)]
    else:
        words = [report.get("cause", "none")]
    return [w for w in words if w and w not in NOT_NAMES]


CONVENTIONS = {"preload", "compression_positive", "colored_noise"}  # rig conventions, not effects: expected word "none"


def category(effects):
    effects = [e for e in effects if e not in CONVENTIONS] or ["none"]
    if effects == ["none"]:
        return "plain"
    if len(effects) > 1:
        return "combined"
    if effects[0] in NEW_WORDS:
        return "new"
    if effects[0] in ("hum", "drift", "clipping", "spikes", "zero_drift"):
        return "oov"
    return "single"


def judge(effects, expected, report):
    if any(e in CONVENTIONS for e in effects):  # judged as the effects without the convention
        expected = [w for e, w in zip(effects, expected) if e not in CONVENTIONS] or ["none"]
        effects = [e for e in effects if e not in CONVENTIONS] or ["none"]
    cause = report.get("cause", "none")
    names = named_words(report)
    cat = category(effects)
    if cat == "plain":
        ok = cause == "none" and not names
    elif cat == "oov":
        ok = cause == "unexplained"
    elif cat == "combined":
        ok = set(expected) - NOT_NAMES <= set(names)
    else:
        ok = cause == expected[0]
    wrong = [n for n in names if n not in expected]
    return cause, names, ok, wrong


def number(d, *keys):
    for k in keys:
        if not isinstance(d, dict) or k not in d:
            return None
        d = d[k]
    return d if isinstance(d, (int, float)) else None


def row(case, truth_path, report_path, wall, cpu, status):
    truth = json.load(open(truth_path))
    effects, expected = truth["effects"], truth["expected"]
    r = {"case": case, "category": category(effects), "expected": expected, "wall_s": float(wall), "cpu_s": float(cpu),
         "status": status, "noise_floor_holdout": truth.get("noise_floor_holdout")}
    try:
        report = json.load(open(report_path))
    except (OSError, ValueError):
        report = None
    if report is None:
        r.update(cause="(" + status + ")", names=[], ok=False, wrong=[], base=None, ext=None)
    else:
        cause, names, ok, wrong = judge(effects, expected, report)
        r.update(cause=cause, names=names, ok=ok, wrong=wrong,
                 base=number(report, "baseline", "error_holdout"),
                 ext=number(report, "extended", "error_holdout"),
                 tool_floor=number(report, "noise_floor", "error_holdout"))
    print(json.dumps(r))


def pct(v):
    return "-" if v is None else "%.2f" % (100 * v)


def table(path):
    rows = [json.loads(line) for line in open(path) if line.strip()]
    head = "%-30s %-26s %-30s %-4s %7s %7s %7s %7s %7s %7s" % (
        "case", "expected", "named (cause; causes)", "ok", "base%", "ext%", "floor%", "tool%", "wall s",
        "cpu s")
    print(head)
    print("-" * len(head))
    for r in rows:
        named = r["cause"] + ("; " + ",".join(r["names"]) if r["names"] and r["names"] != [r["cause"]] else "")
        print("%-30s %-26s %-30s %-4s %7s %7s %7s %7s %7.1f %7.1f" % (
            r["case"], ",".join(r["expected"]), named, "yes" if r["ok"] else "NO",
            pct(r.get("base")), pct(r.get("ext")), pct(r.get("noise_floor_holdout")),
            pct(r.get("tool_floor")), r["wall_s"], r.get("cpu_s", float("nan"))))
    def score(cats):
        sel = [r for r in rows if r["category"] in cats]
        return "%d/%d" % (sum(r["ok"] for r in sel), len(sel))
    wrong = sum(1 for r in rows if r["wrong"])
    wall = sum(r["wall_s"] for r in rows)
    cpu = sum(r.get("cpu_s", 0.0) for r in rows)
    print("-" * len(head))
    print("single: %s, combined/new/out-of-vocabulary: %s, plain: %s, wrong physical names: %d"
          " (cases with a named word not expected); total wall %.0f s, cpu %.0f s" % (
              score({"single"}), score({"combined", "new", "oov"}), score({"plain"}), wrong, wall, cpu))
    print("base%/ext%: held-out error (eq. 27) of plain RT and of the extended model; "
          "floor%: refgen's force-noise floor on the held-out records; tool%: the noise floor "
          "the diagnosis estimated (when it reports one)")


if __name__ == "__main__":
    if len(sys.argv) == 8 and sys.argv[1] == "row":
        row(*sys.argv[2:])
    elif len(sys.argv) == 3 and sys.argv[1] == "table":
        table(sys.argv[2])
    else:
        sys.exit(__doc__)

#!/usr/bin/python3
"""Score `rtb diagnose` reports of blindgen cases.

  score_blind.py [--strict] RUNDIR   (RUNDIR/<case>/truth.json, report.json, wall.txt)

--strict: exit status 1 unless every case is right and no word is wrong.

Rules
  plain (expected none)   correct iff cause == "none" and no named cause
  single word             correct iff cause (the first name) is the expected word
  pair                    correct iff every expected word is among causes[].name
  out of vocabulary       correct iff cause == "unexplained"
A named word (in causes[].name, other than none/unexplained) that is not
expected is a WRONG NAME, counted separately (it does not by itself make a
pair case incorrect, but it is the worse failure for a user).
"""
import json
import os
import sys

NON_NAMES = ("none", "unexplained")
# issue #10's new words: counted with the combinations, as the issue does
NEW_WORDS = ("slack", "relaxation_spectrum", "friction_asymmetry")


def read_json(path):
    try:
        with open(path) as fh:
            return json.load(fh)
    except (OSError, ValueError):
        return None


def names_of(report):
    out = []
    for c in report.get("causes", []) or []:
        n = c.get("name") if isinstance(c, dict) else c
        if n and n not in out:
            out.append(n)
    return out


def judge(truth, report):
    """(category, ok, cause, names, wrong)"""
    exp = truth["expected"]
    if exp == ["none"]:
        cat = "plain"
    elif exp == ["unexplained"]:
        cat = "oov"
    elif len(exp) == 1 and exp[0] in NEW_WORDS:
        cat = "new"
    elif len(exp) == 1:
        cat = "single"
    else:
        cat = "pair"
    if report is None:
        return cat, False, "(no report)", [], []
    cause = report.get("cause", "?")
    names = names_of(report)
    named = [n for n in names if n not in NON_NAMES]
    wrong = [n for n in named if n not in exp]
    if cat == "plain":
        ok = cause == "none" and not named
    elif cat == "oov":
        ok = cause == "unexplained"
    elif cat in ("single", "new"):
        ok = cause == exp[0]
    else:
        ok = all(w in names for w in exp)
    return cat, ok, cause, names, wrong


def main(argv):
    strict = "--strict" in argv[1:]
    args = [a for a in argv[1:] if a != "--strict"]
    if len(args) != 1:
        print(__doc__)
        return 2
    run = args[0]
    rows = []
    for case in sorted(os.listdir(run)):
        d = os.path.join(run, case)
        truth = read_json(os.path.join(d, "truth.json"))
        if truth is None:
            continue
        report = read_json(os.path.join(d, "report.json"))
        wall = "?"
        try:
            with open(os.path.join(d, "wall.txt")) as fh:
                wall = fh.read().split()[0]
        except (OSError, IndexError):
            pass
        status = ""
        try:
            with open(os.path.join(d, "status.txt")) as fh:
                status = fh.read().strip()
        except OSError:
            pass
        cat, ok, cause, names, wrong = judge(truth, report)
        if report is None and status:
            cause = "(%s)" % status
        rows.append((case, cat, "+".join(truth["expected"]), cause, ",".join(names) or "-",
                     ok, ",".join(wrong) or "-", wall))
    w = max([len(r[0]) for r in rows] + [4])
    print("%-*s %-7s %-34s %-20s %-40s %-3s %-20s %6s" % (w, "case", "kind", "expected", "cause", "names",
                                                         "ok", "wrong", "wall s"))
    for r in rows:
        print("%-*s %-7s %-34s %-20s %-40s %-3s %-20s %6s" % (w, r[0], r[1], r[2], r[3], r[4],
                                                             "yes" if r[5] else "NO", r[6], r[7]))

    def count(cats):
        sel = [r for r in rows if r[1] in cats]
        return sum(r[5] for r in sel), len(sel)
    s, c, p = count(("single",)), count(("pair", "new", "oov")), count(("plain",))
    nwrong = sum(len(r[6].split(",")) for r in rows if r[6] != "-")
    print("singles %d/%d, combined/new/oov %d/%d, plain %d/%d, wrong names %d"
          % (s[0], s[1], c[0], c[1], p[0], p[1], nwrong))
    pr, nw, oo = count(("pair",)), count(("new",)), count(("oov",))
    print("  (pairs %d/%d, new words %d/%d, oov %d/%d, cases with a wrong name %d)"
          % (pr[0], pr[1], nw[0], nw[1], oo[0], oo[1], sum(r[6] != "-" for r in rows)))
    if strict and (not rows or nwrong or not all(r[5] for r in rows)):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

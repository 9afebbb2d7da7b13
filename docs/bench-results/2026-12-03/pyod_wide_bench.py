#!/usr/bin/python3
"""Throwaway: old vs new hbos-score, alternating, /usr/bin/time -v; JSON lines + raw text."""
import json, os, re, subprocess, sys, time
D = "/tmp/pyodwide/bench"; os.makedirs(D, exist_ok=True)
bins = {"old": "/tmp/pyodwide/hbos-score-old", "new": "/tmp/pyodwide/hbos-score-new"}
plan = [(f, reps) for f, reps in [("w1e5", 3), ("w1e6", 2), ("t1e6", 3), ("w1e7", 1)]]
if len(sys.argv) > 1: plan = [(a.split(":")[0], int(a.split(":")[1])) for a in sys.argv[1:]]
out = open(f"{D}/results.jsonl", "a"); raw = open(f"{D}/time_v.txt", "a")
def cmds(f, b):
    data = f"/tmp/pyodwide/{f}.csv"; m = f"{D}/{f}.{b}.hbos"
    c = [("fit --mode pyod", ["fit", data, "--no-header", "--mode", "pyod", "-o", m]),
         ("score (PyOD model)", ["score", m, data, "--no-header", "-o", f"{D}/{f}.{b}.score.csv"]),
         ("one shot --mode pyod", [data, "--no-header", "--mode", "pyod", "-q", "-o", f"{D}/{f}.{b}.one.csv"])]
    if f.startswith("t"):
        c.append(("one shot (default mode)", [data, "--no-header", "-q", "-o", f"{D}/{f}.{b}.onedef.csv"]))
    return c
for f, reps in plan:
    for rep in range(reps):
        for b in (["old", "new"] if rep % 2 == 0 else ["new", "old"]):
            for name, args in cmds(f, b):
                load = open("/proc/loadavg").read().split()[:3]
                p = subprocess.run(["/usr/bin/time", "-v", bins[b]] + args, capture_output=True, text=True)
                err = p.stderr
                wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", err).group(1)
                parts = [float(x) for x in wall.split(":")]
                secs = sum(x * 60 ** i for i, x in enumerate(reversed(parts)))
                rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", err).group(1))
                rec = {"input": f, "command": name, "binary": b, "rep": rep, "rc": p.returncode,
                       "wall_s": round(secs, 2), "max_rss_kb": rss, "loadavg": load,
                       "utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
                out.write(json.dumps(rec) + "\n"); out.flush()
                raw.write(f"### {json.dumps(rec)}\n$ hbos-score {' '.join(args)}\n{err}\n"); raw.flush()
                print(json.dumps(rec), flush=True)

"""Summarise the registration runs (stop 50): per depth shift, the later rounds' F median (the
affine field against a constant one, field_significance.py's statistic), the share significant,
|G| x 300 px, and the run's ATE [cm], RPE [mm/frame] and static loss [%], sorted by F.
usage: python3 registration_summary.py DIR (registration_runs.tar.gz unpacked: depth_shift_DX_DY/{fdiag.txt,summary.json})"""
import glob, json, re, statistics as st, sys
d = sys.argv[1]
rows = []
for f in glob.glob(f"{d}/depth_shift_*/fdiag.txt"):
    n = f.split("depth_shift_")[1].split("/")[0]
    L = [l for l in open(f) if l.startswith("FDIAG") and "floor=1.225" in l]
    F = sorted(float(re.search(r"F=(\S+)", l).group(1)) for l in L)
    g = [float(re.search(r"grad=(\S+)", l).group(1)) for l in L]
    s = json.load(open(f"{d}/depth_shift_{n}/summary.json"))
    e = s["evaluation"]
    rows.append((n, st.median(F), sum(x > 2.38 for x in F) / len(F), st.median(g), e["ate"]["rmse"] * 100,
                 e["rpe"]["trans_m"]["rmse"] * 1000, s["static_match_loss_share"] * 100))
print("depth shift (dx_dy px) | F median rounds 2-4 | share p<0.05 | |G|x300 px | ATE cm | RPE mm/frame | statics lost %")
for r in sorted(rows, key=lambda r: r[1]):
    print("%-8s Fmed %5.2f sig %.2f |G|x300 %.3f ATE %.3f RPE %.2f loss %.1f" % r)
# The same frames through the baseline screens (no FDIAG lines: they fit no field).
base = sorted(glob.glob(f"{d}/scr_*/summary.json"))
if base:
    print("\nother screens (today = stop 48's default, the affine-field rows above are stop 47's) | depth shift | ATE cm | RPE mm/frame | statics lost %")
for f in base:
    name = f.split("/")[-2][len("scr_"):]
    screen, shift = name.split("_depth_shift_")
    s = json.load(open(f))
    e = s["evaluation"]
    print("%-6s %-8s ATE %.3f RPE %.2f loss %.1f" % (screen, shift, e["ate"]["rmse"] * 100,
          e["rpe"]["trans_m"]["rmse"] * 1000, s["static_match_loss_share"] * 100))
# Today's default with one part changed at a time, as recorded and with the depth moved up 8 px
# (abl_<option>_<shift>; "xlaterroundsfloor0" = --later-rounds-floor 0, "xrounds1" = --rounds 1,
# "xnotrackhistory" = --no-track-history, "xlaterroundsfieldaffine" = --later-rounds-field affine,
# "x" = nothing changed; "chi2r1" = chi^2 with --rounds 1).
abl = sorted(glob.glob(f"{d}/abl_*/summary.json"))
if abl:
    print("\ntoday's default, one option changed | depth shift | ATE cm | RPE mm/frame | statics lost %")
for f in abl:
    name = f.split("/")[-2][len("abl_"):]
    option, shift = name.rsplit("_", 2)[0], "_".join(name.rsplit("_", 2)[1:])
    s = json.load(open(f))
    e = s["evaluation"]
    print("%-26s %-6s ATE %.3f RPE %.2f loss %.1f" % (option, shift, e["ate"]["rmse"] * 100,
          e["rpe"]["trans_m"]["rmse"] * 1000, s["static_match_loss_share"] * 100))
# The throwaway part switches (part_ablation_env_patch.diff): X_ABL names the default's parts
# turned off (coh = coherence, field = no centring, refit = no refit on the statics, hist = the
# history evidence, gate = the gate at its floor; with "1" in the name in round 1 only;
# "none"/"x" = nothing off). xabl_<parts>_<shift>: 4 rounds; xr1_<parts>_<shift>: --rounds 1;
# xdr_<ratio>_r<rounds>_<shift>: coherence's depth layers X_DR thick.
for prefix, label in (("xabl_", "4 rounds, parts off"), ("xr1_", "1 round, parts off"),
                      ("xdr_", "coherence depth_ratio, rounds")):
    runs = sorted(glob.glob(f"{d}/{prefix}*/summary.json"))
    if runs:
        print(f"\n{label} | depth shift | ATE cm | RPE mm/frame | statics lost %")
    for f in runs:
        name = f.split("/")[-2][len(prefix):]
        head, shift = name.rsplit("_", 2)[0], "_".join(name.rsplit("_", 2)[1:])
        s = json.load(open(f))
        e = s["evaluation"]
        print("%-26s %-6s ATE %.3f RPE %.2f loss %.1f" % (head, shift, e["ate"]["rmse"] * 100,
              e["rpe"]["trans_m"]["rmse"] * 1000, s["static_match_loss_share"] * 100))

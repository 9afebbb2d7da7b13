"""Per hbos-dynbench cell folder, the frames where the rendered people hold more than half of the
screen's survivors, and the largest share of the matches they hold in any frame (stats.csv).
usage: python3 person_share_of_matches.py CELL_DIR..."""
import csv
import sys

for cell in sys.argv[1:]:
    rows = [r for r in csv.DictReader(open(cell + "/stats.csv")) if int(r["matches"]) > 0]
    share = [(int(r["frame"]), int(r["person_matches"]) / int(r["matches"]),
              int(r["person_survivors"]) / max(1, int(r["survivors"]))) for r in rows]
    over = [f for f, _, s in share if s > 0.5]
    print(f"{cell}: people hold > 50 % of the survivors in {len(over)} frames"
          f"{f' ({over[0]}-{over[-1]})' if over else ''}; at most {max(m for _, m, _ in share):.0%} of the matches")

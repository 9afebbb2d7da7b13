import numpy as np, sys
rows, cols, path = int(float(sys.argv[1])), int(float(sys.argv[2])), sys.argv[3]
rng = np.random.default_rng(int(sys.argv[4]) if len(sys.argv) > 4 else 0)
a = rng.integers(0, 10, size=(rows, cols))
with open(path, "w") as f:
    for r in a:
        f.write(",".join(map(str, r.tolist())) + "\n")

"""Stop 28: which match of a dump segment continues which (the keypoint observed in frame f-1 is
the previous keypoint of a match in frame f), for the scripts of this folder."""
import numpy as np


def predecessors(S):
    """Per match, the index of the match it continues, or -1 (columns as static_residuals.py)."""
    frame = S[:, 0].astype(int)
    observed_at = {(frame[i], round(S[i, 8], 2), round(S[i, 9], 2)): i for i in range(len(S))}
    return np.array([observed_at.get((frame[i] - 1, round(S[i, 2], 2), round(S[i, 3], 2)), -1)
                     for i in range(len(S))])

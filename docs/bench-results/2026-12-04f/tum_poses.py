"""Stop 28: TUM trajectories and frame stamps for the scripts of this folder."""
import numpy as np
from scipy.spatial.transform import Rotation as R


def load_poses(path):
    """A TUM trajectory ('stamp tx ty tz qx qy qz qw', camera to world) as {stamp: 4x4}."""
    poses = {}
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        T = np.eye(4)
        T[:3, :3] = R.from_quat(v[4:8]).as_matrix()
        T[:3, 3] = v[1:4]
        poses[v[0]] = T
    return poses


class GroundTruth:
    """A sequence's ground truth, looked up at the pose nearest in time."""

    def __init__(self, sequence_dir):
        self.poses = load_poses(sequence_dir + '/groundtruth.txt')
        self.stamps = np.array(sorted(self.poses))
        self.frame_stamps = [float(a.split()[0]) for a in open(sequence_dir + '/rgb.txt')
                             if not a.startswith('#')]

    def at(self, t):
        return self.poses[self.stamps[np.argmin(abs(self.stamps - t))]]

    def motion(self, f):
        """T_cur_prev of frame f: the previous camera's points in the current camera."""
        return np.linalg.inv(self.at(self.frame_stamps[f])) @ self.at(self.frame_stamps[f - 1])

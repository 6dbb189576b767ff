"""Vertices (n x 2) and 0-based triangles (m x 3) of a medit .mesh file (ASCII), as numpy arrays.

Shared by the analysis scripts (corner_h1_bands.py, front_l2_dwr.py, triangle_shape_efficiency.py);
every other section of the file is skipped.
"""
import numpy as np


def read_medit(path):
    tok = open(path).read().split()
    i, P, T = 0, None, None
    while i < len(tok):
        if tok[i] == 'Vertices':
            n = int(tok[i + 1])
            P = np.array(tok[i + 2:i + 2 + 3 * n], float).reshape(n, 3)[:, :2]
            i += 2 + 3 * n
        elif tok[i] == 'Triangles':
            n = int(tok[i + 1])
            T = np.array(tok[i + 2:i + 2 + 4 * n], int).reshape(n, 4)[:, :3] - 1
            i += 2 + 4 * n
        else:
            i += 1
    return P, T

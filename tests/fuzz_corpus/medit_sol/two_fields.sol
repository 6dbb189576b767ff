MeshVersionFormatted 2
SolAtVertices
2
2 3 2
1e4 -2.5e3 9e4 0.1 0.2
1e-2 0 1e-2 -3 4
End

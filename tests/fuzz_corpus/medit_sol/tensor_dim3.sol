MeshVersionFormatted 2
Dimension 3
SolAtVertices
2
2 3 1
4 0 0 9 0 16 0.5
1 0 0 1 0 1 2
End

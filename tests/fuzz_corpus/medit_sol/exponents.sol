MeshVersionFormatted 2
Dimension 2
SolAtVertices
4
1 1
1e-3
2.5E-2
0.0625
1.0e+1
End

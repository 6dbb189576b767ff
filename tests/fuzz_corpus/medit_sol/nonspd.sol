MeshVersionFormatted 2

Dimension 2

SolAtVertices
5
1 3

100 0 100
100 0 100
100 0 100
100 0 100
1 2 1

End

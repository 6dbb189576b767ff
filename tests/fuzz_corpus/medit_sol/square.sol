MeshVersionFormatted 2

Dimension 2

SolAtVertices
5
1 3

100 0 100
100 0 100
400 0 25
100 0 100
200 50 100

End

MeshVersionFormatted 1

Dimension 2

SolAtVertices
4
1 3

# metric written by FreeFem++ savesol
4 0 4
4 1 4
4 0 4
9 0 1

End

# The largest sphere inside the cube [-1, 1]^3 (tests/data/cube.off).
1 0 0
v 0 0 0 1

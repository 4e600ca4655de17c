2 1 0
v 0 0 0 1
v inf 0 0 1
e 0 1

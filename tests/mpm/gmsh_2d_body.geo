// Body for tests/mpm/gmsh_2d: a quadrilateral block with a slanted top.
Point(1) = {0.5, 0.75, 0}; Point(2) = {1.5, 0.75, 0}; Point(3) = {1.5, 1.25, 0}; Point(4) = {0.5, 1.5, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 5; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface(0) = {1};
Mesh.MshFileVersion = 2.2;

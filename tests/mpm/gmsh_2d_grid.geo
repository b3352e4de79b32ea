// Background grid for tests/mpm/gmsh_2d: 2 m x 2 m, 8 x 8 quadrilaterals,
// slightly skewed interior so that the grid is not Cartesian.
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 2, 0}; Point(4) = {0, 2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 9; Transfinite Surface{1}; Recombine Surface{1};
Physical Curve(2) = {1};   // floor: boundary id 2
Physical Curve(1) = {2, 3, 4};
Physical Surface(0) = {1};
Mesh.MshFileVersion = 2.2;

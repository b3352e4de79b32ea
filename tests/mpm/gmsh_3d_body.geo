// Body for tests/mpm/gmsh_3d_body: a hexahedral block 0.5 x 0.5 x 0.25 m.
Point(1) = {0.25, 0.25, 0.5}; Point(2) = {0.75, 0.25, 0.5}; Point(3) = {0.75, 0.75, 0.5}; Point(4) = {0.25, 0.75, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Extrude {0, 0, 0.25} { Surface{1}; Layers{1}; Recombine; }
Physical Volume(0) = {1};
Mesh.MshFileVersion = 2.2;

// Planar sudden expansion 1:2 (slump scene "expansion"): the upper half of a
// channel of half-width h = 1 for -Lu <= x <= 0 opening into one of
// half-width 2h for 0 <= x <= Ld; y = 0 is the symmetry plane.
// Regenerate: gmsh -2 -format msh22 -setnumber s 1 expansion.geo -o expansion.msh
// (s scales every element size). Physical tags start at 101: PETSc 3.18's
// Gmsh reader also files elements whose elementary tag equals a physical
// tag under that group (docs/exact.md).
If (!Exists(s))
  s = 1;
EndIf
h = 1; Lu = 10; Ld = 30;
hc = 0.04 * s;  // at the re-entrant corner
hm = 0.1 * s;   // around the step
hf = 0.5 * s;   // far up- and downstream
Point(1) = {-Lu, 0, 0, hf};
Point(2) = {0, 0, 0, hm};
Point(3) = {Ld, 0, 0, hf};
Point(4) = {Ld, 2 * h, 0, hf};
Point(5) = {0, 2 * h, 0, hm};
Point(6) = {0, h, 0, hc};
Point(7) = {-Lu, h, 0, hf};
Point(8) = {6 * h, 0, 0, hm};
Point(9) = {6 * h, 2 * h, 0, hm};
Line(1) = {1, 2};
Line(2) = {2, 8};
Line(3) = {8, 3};
Line(4) = {3, 4};
Line(5) = {4, 9};
Line(6) = {9, 5};
Line(7) = {5, 6};
Line(8) = {6, 7};
Line(9) = {7, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9};
Plane Surface(1) = {1};
Physical Curve("inlet", 101) = {9};
Physical Curve("outlet", 102) = {4};
Physical Curve("wall", 103) = {5, 6, 7, 8};
Physical Curve("symmetry", 104) = {1, 2, 3};
Physical Surface("fluid", 105) = {1};

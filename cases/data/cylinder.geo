// Flow past a cylinder between two walls (slump scene "cylinder"): the upper
// half of the channel -Lu <= x <= Ld, 0 <= y <= H with the cylinder of
// radius R at the origin cut out; y = 0 is the symmetry plane.
// Blockage R/H = 1/2 (the classic confined-cylinder benchmark).
// Regenerate: gmsh -2 -format msh22 -setnumber s 1 cylinder.geo -o cylinder.msh
// (s scales every element size: s = 0.5 halves them).
If (!Exists(s))
  s = 1;
EndIf
R = 1; H = 2; Lu = 15; Ld = 15;
hc = 0.06 * s;   // on the cylinder
hw = 0.15 * s;   // on the wall above it
hf = 0.6 * s;    // far up- and downstream
Point(1) = {-Lu, 0, 0, hf};
Point(2) = {-R, 0, 0, hc};
Point(3) = {0, 0, 0, hc};
Point(4) = {R, 0, 0, hc};
Point(5) = {Ld, 0, 0, hf};
Point(6) = {Ld, H, 0, hf};
Point(7) = {0, H, 0, hw};
Point(8) = {-Lu, H, 0, hf};
Point(9) = {0, R, 0, hc};
Point(10) = {3 * R, 0, 0, 2 * hc};  // the wake on the axis
Line(1) = {1, 2};
Circle(2) = {2, 3, 9};
Circle(3) = {9, 3, 4};
Line(4) = {4, 10};
Line(5) = {10, 5};
Line(6) = {5, 6};
Line(7) = {6, 7};
Line(8) = {7, 8};
Line(9) = {8, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9};
Plane Surface(1) = {1};
// physical tags far from the elementary ones: PETSc 3.18's Gmsh reader
// (-dm_plex_gmsh_use_regions) also put the elements whose elementary tag
// equals a physical tag into that region's label (Line 5 into "cylinder")
Physical Curve("inlet", 101) = {9};
Physical Curve("outlet", 102) = {6};
Physical Curve("wall", 103) = {7, 8};
Physical Curve("symmetry", 104) = {1, 4, 5};
Physical Curve("cylinder", 105) = {2, 3};
Physical Surface("fluid", 106) = {1};

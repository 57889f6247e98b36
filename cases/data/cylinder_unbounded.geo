// A cylinder in a uniform stream (slump scene "cylinder -cylinder_domain
// unbounded"; Tokpavi, Magnin & Jay 2008, Riber's thesis Fig. 40): the upper
// half of the box -Lu <= x <= Ld, 0 <= y <= H around the cylinder of radius
// R = 1 at the origin; y = 0 is the symmetry plane. The element size grows
// from hc on the cylinder with the distance from it, up to hf.
// Regenerate: gmsh -2 -format msh22 -setnumber s 1 cylinder_unbounded.geo -o cylinder_unbounded.msh
// (s scales every element size: s = 0.5 halves them). Physical tags from 101:
// see cylinder.geo.
If (!Exists(s))
  s = 1;
EndIf
R = 1; H = 30; Lu = 40; Ld = 50;
hc = 0.04 * s; hf = 4 * s;
Point(1) = {-Lu, 0, 0, hf};
Point(2) = {-R, 0, 0, hc};
Point(3) = {0, 0, 0, hc};
Point(4) = {R, 0, 0, hc};
Point(5) = {Ld, 0, 0, hf};
Point(6) = {Ld, H, 0, hf};
Point(7) = {-Lu, H, 0, hf};
Point(8) = {0, R, 0, hc};
Line(1) = {1, 2};
Circle(2) = {2, 3, 8};
Circle(3) = {8, 3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].EdgesList = {2, 3};
Field[1].NNodesByEdge = 200;
Field[2] = MathEval;
Field[2].F = Sprintf("Min(%g + 0.08 * %g * F1 + 0.02 * %g * F1 * F1, %g)", hc, s, s, hf);
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Physical Curve("inlet", 101) = {7};
Physical Curve("outlet", 102) = {5};
Physical Curve("far", 103) = {6};
Physical Curve("symmetry", 104) = {1, 4};
Physical Curve("cylinder", 105) = {2, 3};
Physical Surface("fluid", 106) = {1};

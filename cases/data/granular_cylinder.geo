// Dense granular chute flow over a cylinder (slump scene "granular_cylinder";
// Chauchat & Medale 2014, section 4.2), in grain diameters d: the channel is
// W = 20 D wide and L = 30 D long, the cylinder of diameter D = 10 d sits at
// its centre (the origin). The flow goes along -x. This is the half
// 0 <= y <= W/2 of the channel: y = 0 is the symmetry plane, y = W/2 the
// rough wall. Element sizes: hc on the cylinder, growing with the distance
// from it; hw on the wall, whose shear layer carries the flow; hf elsewhere.
// Regenerate: gmsh -2 -format msh22 -setnumber s 1 granular_cylinder.geo -o granular_cylinder.msh
// (s scales every element size). Physical tags from 101: see cylinder.geo.
If (!Exists(s))
  s = 1;
EndIf
R = 5; W2 = 100; L2 = 150;
hc = 0.3 * s; hw = 2 * s; hf = 8 * s;
Point(1) = {-L2, 0, 0, hf};
Point(2) = {-R, 0, 0, hc};
Point(3) = {0, 0, 0, hc};
Point(4) = {R, 0, 0, hc};
Point(5) = {L2, 0, 0, hf};
Point(6) = {L2, W2, 0, hw};
Point(7) = {-L2, W2, 0, hw};
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
Field[2].F = Sprintf("Min(%g + 0.12 * %g * F1, %g)", hc, s, hf);
Field[3] = MathEval;
Field[3].F = Sprintf("%g + 0.25 * %g * (%g - y)", hw, s, W2);
Field[4] = Min;
Field[4].FieldsList = {2, 3};
Background Field = 4;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Physical Curve("top_end", 101) = {5};
Physical Curve("bottom_end", 102) = {7};
Physical Curve("wall", 103) = {6};
Physical Curve("symmetry", 104) = {1, 4};
Physical Curve("cylinder", 105) = {2, 3};
Physical Surface("granular", 106) = {1};

% DEMO-PLATE  Stanok demo (AxiOMA): a 60 x 40 mm plate contour with rounded corners and a helical bore
G17 G90 G15 G191 G71 G72 G172 G272 G94 G97 G49 G40 G00 G80 G98
G53 G153 G193 G64 BRISK CUT2DF ORIAXES // safety line
; a 10 mm end mill is in the spindle (the built-in mill keeps no tool table)
N20 MSG("Contour")
N30 S6000 M3 M8
N40 G0 X-5 Y0 Z5
N50 G1 Z-3 F300
N60 G1 X50 F800
N70 G3 X60 Y10 CR=10                   ; corner radius 10, centre (50,10)
N80 G1 Y30
N90 G3 X50 Y40 R10                     ; centre (50,30)
N100 G1 X10
N110 G3 X0 Y30 I0 J-10                 ; centre (10,30), relative (G191)
N120 G1 Y10
N130 G3 X10 Y0 I10 J0                  ; centre (10,10)
N140 G0 Z5
N150 MSG("Helical bore")
N160 G0 X40 Y20
N170 G1 Z0 F300
N180 G2 X40 Y20 Z-6 I-5 J0 P2 F600     ; helix about (35,20): 1 + 2 extra turns, Z 0 -> -6
N190 G2 I-5 J0                         ; a full circle at depth to clean the bottom
N200 G0 Z5
N210 MSG()
N220 G04 X1.5
N230 M5 M9
N240 G0 X0 Y0 Z50
N250 M30

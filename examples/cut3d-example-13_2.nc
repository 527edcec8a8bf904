; AxiOMA 3D peripheral compensation CUT3DC with insertion depth ISD, after the manual's example
; 13.2 (§13.3): the programmed contour first (N40-N70), then the same contour compensated
; (N110-N140) for a flat end mill R5 (T1 of examples/cut3d-tools.toml). The entry N110 goes
; straight to the offset start; ISD goes 0 -> 20 along N120 and 20 -> 40 along N130, an arc of
; radius R about the vertex (at depth 20) bypasses the outer corner (30, 30); the exit N140 goes
; straight back to the programmed point. Plot: docs/cut3d.md.
G17 G90 G191 G71 G94 G49 G40 G64 CUT2DF ORIAXES
N10 M6 T1
N20 TRAORI
N30 G01 X-20 Y0 Z0 F1800
N40 X0 Y0
N50 X30 Y30
N60 X60 Y0
N70 X90
N80 G00 Z20
N90 X-20 Y0
N100 G01 Z0
N110 CUT3DC G41 X0 Y0
N120 X30 Y30 ISD=20
N130 X60 Y0 ISD=40
N140 G40 X90
N150 M30

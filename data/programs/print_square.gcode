; A SMALL PRINT: two layers of a 20 mm square wall with a diagonal infill, for a Marlin printer
; written by hand for biscara; place it with: biscara joints print_square.gcode --origin -10,270,0,0 (the bed's corner)
; E: filament, mm (1.75 mm filament, 0.4 mm line, 0.2 mm layers)
M82 ; absolute extrusion
M104 S205 ; hotend temperature
M140 S60 ; bed temperature
M190 S60 ; wait for the bed
M109 S205 ; wait for the hotend
G28 ; home
G92 E0
; LAYER:0
G1 Z0.2 F600
G0 X0 Y0 F3000
G1 X20 Y0 E0.6660 F1200
G1 X20 Y20 E1.3320
G1 X0 Y20 E1.9980
G1 X0 Y0 E2.6640
G1 E1.8640 F2400 ; retract
G0 X2 Y2 F3000
G1 E2.6640 F2400 ; prime
G1 X18 Y18 E3.4175 F1200 ; infill
G1 E2.6175 F2400 ; retract
; LAYER:1
G1 Z0.4 F600
G0 X0 Y0 F3000
G1 E3.4175 F2400 ; prime
G1 X20 Y0 E4.0835 F1200
G1 X20 Y20 E4.7495
G1 X0 Y20 E5.4155
G1 X0 Y0 E6.0815
G1 E5.2815 F2400 ; retract
G0 X18 Y2 F3000
G1 E6.0815 F2400 ; prime
G1 X2 Y18 E6.8350 F1200 ; infill
G1 E6.0350 F2400 ; retract
G0 Z10 F600
M104 S0 ; hotend off
M140 S0 ; bed off
M84 ; motors off

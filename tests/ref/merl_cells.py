#!/usr/bin/python3
"""merl_cells.py: how many MERL cells have their centre above the horizon
(tests/data/test_merl.c, test_format.c), computed without brdffit.

A cell (i, j, k) of MERL's 90 x 90 x 180 table (SPEC §8) has its centre at
theta_h = ((i + 1/2)/90)^2 pi/2, theta_d = (j + 1/2)/90 pi/2,
phi_d = (k + 1/2)/180 pi. With the half vector at phi_h = 0 and
d = (sin td cos pd, sin td sin pd, cos td) the difference vector, the
directions are R_y(theta_h) d and R_y(theta_h) (-d_x, -d_y, d_z), whose z
components are cos td cos th -/+ sin td cos pd sin th: both are >= 0 when
cos td cos th >= |sin td cos pd sin th|.

Prints the count for a fully valid table and for the test's table whose
every seventh cell (cell % 7 == 3) is invalid: 1096216 939619.
"""
import math

total = 0
valid = 0
for i in range(90):
    th = ((i + 0.5) / 90) ** 2 * math.pi / 2
    for j in range(90):
        td = (j + 0.5) / 90 * math.pi / 2
        for k in range(180):
            pd = (k + 0.5) / 180 * math.pi
            if math.cos(td) * math.cos(th) >= abs(
                    math.sin(td) * math.cos(pd) * math.sin(th)):
                total += 1
                valid += (k + 180 * (j + 90 * i)) % 7 != 3
print(total, valid)

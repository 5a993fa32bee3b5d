"""Martin & Moyce (1952), Phil. Trans. R. Soc. A 244, 312-324, table 2: the surge front of a
collapsing water column, rectangular section, plane symmetry, n² = 2 (height 2a on a base a),
the mean of nine runs at a = 2.25 in. Z = z/a is the front's distance from the wall behind the
column; T = n t √(g/a) = t √(2g/a). The paper shifts each run's time so that T = 1.19 at Z = 1.44
(the release of the column took a moment). The same table's mean at a = 1.125 in is in
MEAN_HALF_SIZE. Transcribed from the printed table as reproduced in several validation suites
(they agree to 0.01)."""

T_ALIGN, Z_ALIGN = 1.19, 1.44

# (T, Z), a = 2.25 in
MEAN = [(0.41, 1.11), (0.84, 1.22), (1.19, 1.44), (1.43, 1.67), (1.63, 1.89), (1.83, 2.11), (1.98, 2.33),
        (2.20, 2.56), (2.32, 2.78), (2.51, 3.00), (2.65, 3.22), (2.83, 3.44), (2.97, 3.67), (3.11, 3.89),
        (3.33, 4.11)]
# (T, Z), a = 1.125 in
MEAN_HALF_SIZE = [(0.82, 1.22), (1.19, 1.44), (1.58, 1.89), (1.91, 2.33), (2.23, 2.78), (2.58, 3.22),
                  (2.91, 3.67), (3.26, 4.11)]

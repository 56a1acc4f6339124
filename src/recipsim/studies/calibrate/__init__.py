"""Calibration of uncertain case parameters against measured or catalogue points
(``recipsim calibrate``, :func:`recipsim.calibrate`): :mod:`.data` reads the points,
:mod:`.fit` fits with bounded least squares and judges identifiability and confidence,
:mod:`.report` writes the result and the calibrated case."""

"""What the study makes of the impacts: rigid-body theory, critical angles and fits, calibration,
the inverse map, figures, the reproduction of the study and the accuracy study."""

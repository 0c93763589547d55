"""Profile / cut-out: a contour cut inside, outside or on a shape's outlines, with tabs, leads and
ramped step-downs (:mod:`.profile`), as an operation kind of the job model (:mod:`.kind`)."""

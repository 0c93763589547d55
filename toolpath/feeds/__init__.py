"""Materials, feeds and speeds: the published chip loads and surface speeds (:mod:`.materials`),
the calculator (:mod:`.calculator`) and the check of a planned program (:mod:`.programcheck`)."""

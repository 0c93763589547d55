"""Pocketing: clearing any closed region (with islands) with a flat end mill; finishing and rest
machining (:mod:`.pocket`, the paths in :mod:`.clearing`, the job model's kind in :mod:`.kind`)."""

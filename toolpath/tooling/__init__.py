"""The tool library (:mod:`.library`), its file formats (:mod:`.formats`) and its file on disk
(:mod:`.store`)."""

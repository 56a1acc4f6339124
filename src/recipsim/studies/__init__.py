"""Studies built on the pipeline: operating maps (:mod:`.sweep`), comparisons
(:mod:`.compare`), the paper's pinned-against-flexible study (:mod:`.paper`), speed
against error (:mod:`.bench`) and the hard-case check (:mod:`.check`).
"""

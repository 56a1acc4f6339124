"""The bearing laws of the flexible crank train: one module per law, registered in
:mod:`.registry` (the slot's registry, its compiled dispatch and the contract for adding
a law)."""

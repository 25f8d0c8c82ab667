"""The load models (:mod:`.registry` holds them by name): ``linear`` (:mod:`.linear`),
``compliance`` (:mod:`.compliance`) and ``surface`` (:mod:`.surface`)."""

// placeholder: World::snapshot / World::restore (in progress)

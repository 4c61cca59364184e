"""etswarm.sim."""

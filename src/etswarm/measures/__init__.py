"""etswarm.measures."""

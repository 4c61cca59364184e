"""etswarm.experiments."""

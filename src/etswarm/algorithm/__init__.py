"""etswarm.algorithm."""

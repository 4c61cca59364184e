"""etswarm.shapes."""

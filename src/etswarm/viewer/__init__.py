"""etswarm.viewer."""

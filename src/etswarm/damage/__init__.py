"""etswarm.damage."""

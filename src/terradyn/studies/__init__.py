"""Named experiments: each a plain function returning a result."""

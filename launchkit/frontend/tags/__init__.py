"""Tag parsers: one function per tag, turning an entity into its action (any syntax)."""

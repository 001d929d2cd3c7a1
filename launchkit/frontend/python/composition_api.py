"""Placeholder."""

from launchkit.frontend.python.values import unsupported

ComposableNodeContainer = unsupported("ComposableNodeContainer")
LoadComposableNodes = unsupported("LoadComposableNodes")
ComposableNode = unsupported("ComposableNode")

"""What a launch file means, independent of its syntax: actions, substitutions, conditions."""

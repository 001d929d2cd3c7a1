"""Lockstep simulated time: a launch's clock advances only when every participant is done.

The launcher hosts the time authority (:mod:`.authority`): it publishes ``/clock`` and moves
it to the next instant something is due once every participant (:mod:`.participant`, one per
ROS context of a process started with ``LAUNCHKIT_LOCKSTEP=1``) has reported itself idle at
the current instant and every message sent so far has been handled by the participants that
subscribe to it (:mod:`.quiescence` holds that rule). Reports travel on the transport
(:mod:`.report`), beside the ROS graph, not in it. ``docs/simulation.md`` tells the story.
"""

"""Launching on other hosts: ``launchkit agent`` runs a host's share of a launch.

A launch file marks entities for a host (``<group machine="NAME">``); the launcher starts them
through that host's agent, which runs them in process groups of their own under its orphan
guard and streams their output and exits back, and the launcher supervises them like its own
processes (the same :class:`~launchkit.runtime.lifecycle.Lifecycle`: respawn, the SIGINT,
SIGTERM, SIGKILL ladder, ``[name-N]`` prefixes). The agent stops a launch's processes by itself
when the launcher is gone for the grace period (killed, or the link lost).

Module map: ``protocol`` (keys, sealed messages, a process spec on the wire), ``keys`` (the
shared agent key), ``agent_processes`` (the agent's process table), ``agent`` (the agent: its
session, requests, launcher watch, loop), ``remote_process`` (a process on another host, as the
launcher's supervisor sees it), ``hosts`` (the launcher's side: session, agents, requests),
``cli`` (``launchkit agent``).
"""

"""Running a launch: the supervisor loop, process lifecycle, output, signals and logs."""

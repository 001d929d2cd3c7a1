"""``launchkit build``: a ROS 2 workspace built the colcon way, for what pip can build.

Packages are found (:mod:`.discovery`) by their package.xml (:mod:`.manifest`,
:mod:`.conditions`), ordered (:mod:`.graph`), checked and decided on (:mod:`.known`,
:mod:`.plan`, :mod:`.cmake_plan` with :mod:`.cmake_lexer` and :mod:`.cmake_rules`), built
(:mod:`.pip_build` with :mod:`.symlink_install` and :mod:`.dist_record`; :mod:`.cmake_install`)
into the ament layout (:mod:`.ament_layout`) by :mod:`.builder`, which reports
(:mod:`.report`), keeps the workspace's folders (:mod:`.folders`) and runs pip
(:mod:`.processes`); :mod:`.setup_scripts` writes ``install/setup.sh``.
"""

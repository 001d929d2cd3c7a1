# Pattern: ros2/demos lifecycle/launch/lifecycle_demo.launch.py (a LifecycleNode driven by
# ChangeState events from OnStateTransition handlers, and a client that ends the launch).
import launch
from launch import LaunchDescription
from launch.actions import EmitEvent, LogInfo, RegisterEventHandler
from launch_ros.actions import LifecycleNode, Node
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState

import lifecycle_msgs.msg


def generate_launch_description():
    talker_node = LifecycleNode(package='lifecycle', executable='lifecycle_talker',
                                name='lc_talker', namespace='', output='screen')
    listener_node = Node(package='lifecycle', executable='lifecycle_listener', output='screen')
    service_client = Node(package='lifecycle', executable='lifecycle_service_client',
                          output='screen', on_exit=launch.actions.Shutdown())

    return LaunchDescription([
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker_node, goal_state='inactive',
            entities=[
                LogInfo(msg="node 'lc_talker' reached the 'inactive' state, 'activating'."),
                EmitEvent(event=ChangeState(
                    lifecycle_node_matcher=launch.events.matches_action(talker_node),
                    transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE,
                )),
            ],
        )),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker_node, goal_state='active',
            entities=[LogInfo(msg="node 'lc_talker' reached the 'active' state.")],
        )),
        talker_node,
        listener_node,
        EmitEvent(event=ChangeState(
            lifecycle_node_matcher=launch.events.matches_action(talker_node),
            transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE,
        )),
        service_client,
    ])

from launch import LaunchDescription

settings = {}
value = settings["missing"]

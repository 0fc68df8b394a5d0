"""syncap view: the system's LCM traffic, live or from a recording, shown with Rerun (issue 19).

Modules: bindings (the message types generated from proto/msg at run time), contour (the
silhouette codec), parts (joining split messages), cameras (cameras.json as Rerun pinholes),
logger (one method per message type), sources (LCM log files, live LCM), cli (options, main).
"""

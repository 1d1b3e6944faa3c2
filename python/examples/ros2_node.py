"""A ROS 2 node that explains the map as rooms: subscribes to ``/map``
(``nav_msgs/OccupancyGrid``) and publishes the rooms.

* ``/rooms`` (``std_msgs/String``): ``world.json``'s rooms as JSON (id, type, units, area in
  m², doors, the rooms each opens to);
* ``/room_labels`` (``nav_msgs/OccupancyGrid``): the map's cells labelled with their room's id
  (0 for none, ids above 100 wrap into 1 - 100, as an OccupancyGrid holds at most 100), on the
  map's own grid, so RViz shows it over the map.

Written against the ``rclpy`` API (Humble and later) and **untested where no ROS 2 is
installed**, as on the machines that build this package: ``make test`` checks only that it
compiles. Run it with ``python3 ros2_node.py`` in a sourced ROS 2 environment with ``ksmcmc``
installed (``pip install ./python``). The chain runs without the GIL in a worker thread, so
the node keeps spinning while a map is explained; a new map while one is being explained
waits for the next round.
"""

import json
import threading

import numpy as np
import rclpy
from nav_msgs.msg import OccupancyGrid
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile
from std_msgs.msg import String

import ksmcmc


class RoomsNode(Node):
    def __init__(self):
        super().__init__("ksmcmc_rooms")
        self.declare_parameter("seed", 1)
        self.declare_parameter("iterations", 20000)
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        self.rooms_pub = self.create_publisher(String, "rooms", latched)
        self.labels_pub = self.create_publisher(OccupancyGrid, "room_labels", latched)
        self.create_subscription(OccupancyGrid, "map", self.on_map, latched)
        self.busy = threading.Lock()
        self.pending = None

    def on_map(self, msg: OccupancyGrid):
        self.pending = msg
        if self.busy.acquire(blocking=False):
            threading.Thread(target=self.explain_pending, daemon=True).start()

    def explain_pending(self):
        try:
            while self.pending is not None:
                msg, self.pending = self.pending, None
                self.explain(msg)
        finally:
            self.busy.release()

    def explain(self, msg: OccupancyGrid):
        info = msg.info
        # An OccupancyGrid's data starts at the bottom row; ksmcmc reads rows from the top.
        grid = np.asarray(msg.data, dtype=np.int8).reshape(info.height, info.width)[::-1]
        origin = (info.origin.position.x, info.origin.position.y, yaw_of(info.origin.orientation))
        plan = ksmcmc.floorplan(
            grid,
            resolution=info.resolution,
            origin=origin,
            seed=self.get_parameter("seed").value,
            iterations=self.get_parameter("iterations").value,
        )
        self.get_logger().info(f"{len(plan.rooms)} rooms on a {info.width}x{info.height} map")
        self.rooms_pub.publish(String(data=json.dumps(plan.rooms)))
        labels = plan.labels[::-1].astype(np.int64)
        wrapped = np.where(labels == 0, 0, (labels - 1) % 100 + 1).astype(np.int8)
        out = OccupancyGrid()
        out.header = msg.header
        out.info = info
        out.data = wrapped.ravel().tolist()
        self.labels_pub.publish(out)


def yaw_of(q) -> float:
    """The yaw of a quaternion (rotation about z)."""
    import math

    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def main():
    rclpy.init()
    node = RoomsNode()
    try:
        rclpy.spin(node)
    finally:
        node.destroy_node()
        rclpy.shutdown()


if __name__ == "__main__":
    main()

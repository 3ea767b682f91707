#!/usr/bin/python3
"""A pymodbus 3.0 TCP server with known contents, for the bridge tests.
usage: pymodbus_server.py PORT"""
import sys

from pymodbus.datastore import ModbusSequentialDataBlock, ModbusServerContext, ModbusSlaveContext
from pymodbus.server import StartTcpServer

port = int(sys.argv[1])
hr = [0] * 100
hr[10], hr[11] = 0x4048, 0xF5C3          # float32 3.14 ABCD
hr[20] = 0xFFFE                          # int16 -2
hr[30:34] = [0x0000, 0x0000, 0x0001, 0x0000]  # uint64 0x0000_0000_0001_0000 ABCD... = 65536
ir = [0] * 100
ir[3] = 777
co = [False] * 100
co[5] = True
store = ModbusSlaveContext(
    co=ModbusSequentialDataBlock(0, co), di=ModbusSequentialDataBlock(0, [False] * 100),
    hr=ModbusSequentialDataBlock(0, hr), ir=ModbusSequentialDataBlock(0, ir), zero_mode=True)
print("pymodbus server on port %d" % port, flush=True)
StartTcpServer(context=ModbusServerContext(slaves=store, single=True), address=("127.0.0.1", port),
               allow_reuse_address=True)

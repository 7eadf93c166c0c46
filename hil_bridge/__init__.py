"""The firmware link over a wire (docs/protocol.md): the Python codec, the
serial and CAN links, the host boards, fault injection and the DBC."""

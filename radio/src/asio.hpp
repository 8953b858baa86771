// Private to the radio module: the Boost.Asio headers the transports use, in one
// place. GCC 12 reports -Wnull-dereference inside Asio 1.74's scheduler
// (compensating_work_started(), once inlined) although it is a system header; that
// code runs only on a thread inside the scheduler, where the pointer is set, so the
// warning is silenced for these headers only.
#pragma once

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/asio/buffer.hpp>
#include <boost/asio/error.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/serial_port.hpp>
#include <boost/asio/write.hpp>
#pragma GCC diagnostic pop

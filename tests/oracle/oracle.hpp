// Independent reference solvers used only by tests and benchmarks (slow, obviously correct).
#pragma once

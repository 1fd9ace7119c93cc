# sdk/sdk.mk — the client SDK's sources (C99, fixed-point, allocation-free).
CLIENT_SRCS += $(sort $(wildcard sdk/src/*.c))

#pragma once
// Everything in one include. Prefer the specific headers in larger code bases.

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"
#include "freeform/core/polynomial.h"
#include "freeform/core/types.h"
#include "freeform/curve/batch.h"
#include "freeform/curve/bezier_curve.h"
#include "freeform/io/document.h"
#include "freeform/io/file.h"

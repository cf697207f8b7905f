/* GEOS, opened on first use (lazylib.h): the functions lamina calls, and
 * each name #defined to its pointer, so that code written against
 * <geos_c.h> stays as it is. A call to a GEOS function missing from the
 * list fails to link (lamina does not link GEOS); one in the list without
 * its #define fails to link the same way, and a #define without its
 * entry does not compile. Include this header, not <geos_c.h>; every
 * GEOS call needs a context from lam_geos_init (geos.h), which loads the
 * library first. */
#ifndef LAM_GEOS_LAZY_H
#define LAM_GEOS_LAZY_H

#include <geos_c.h>

#include "lazylib.h"

/* Load GEOS (libgeos_c.so.1) if not yet loaded; thread-safe. Errors:
 * LAM_EIO "cannot load libgeos_c.so.1: ...; install libgeos-c1v5". */
int lam_geos_load(lam_error *err);

#define LAM_GEOS_FUNCS(X)                     \
    X(GEOSArea_r)                             \
    X(GEOSBufferWithStyle_r)                  \
    X(GEOSClipByRect_r)                       \
    X(GEOSConstrainedDelaunayTriangulation_r) \
    X(GEOSContext_setErrorMessageHandler_r)   \
    X(GEOSCoordSeq_create_r)                  \
    X(GEOSCoveredBy_r)                        \
    X(GEOSCoordSeq_getSize_r)                 \
    X(GEOSCoordSeq_getXY_r)                   \
    X(GEOSCoordSeq_setXY_r)                   \
    X(GEOSDifference_r)                       \
    X(GEOSDifferencePrec_r)                   \
    X(GEOSGeomGetX_r)                         \
    X(GEOSGeomGetY_r)                         \
    X(GEOSGeomTypeId_r)                       \
    X(GEOSGeom_clone_r)                       \
    X(GEOSGeom_createCollection_r)            \
    X(GEOSGeom_createLineString_r)            \
    X(GEOSGeom_createLinearRing_r)            \
    X(GEOSGeom_createPolygon_r)               \
    X(GEOSGeom_destroy_r)                     \
    X(GEOSGeom_getCoordSeq_r)                 \
    X(GEOSGeom_getXMax_r)                     \
    X(GEOSGeom_getXMin_r)                     \
    X(GEOSGeom_getYMax_r)                     \
    X(GEOSGeom_getYMin_r)                     \
    X(GEOSGetExteriorRing_r)                  \
    X(GEOSGetGeometryN_r)                     \
    X(GEOSGetInteriorRingN_r)                 \
    X(GEOSGetNumGeometries_r)                 \
    X(GEOSGetNumInteriorRings_r)              \
    X(GEOSIntersection_r)                     \
    X(GEOSIntersectionPrec_r)                 \
    X(GEOSMakeValidParams_create_r)           \
    X(GEOSMakeValidParams_destroy_r)          \
    X(GEOSMakeValidParams_setKeepCollapsed_r) \
    X(GEOSMakeValidParams_setMethod_r)        \
    X(GEOSMakeValidWithParams_r)              \
    X(GEOSPointOnSurface_r)                   \
    X(GEOSPolygonize_r)                       \
    X(GEOSUnaryUnion_r)                       \
    X(GEOSUnaryUnionPrec_r)                   \
    X(GEOSUnionPrec_r)                        \
    X(GEOS_finish_r)                          \
    X(GEOS_init_r)                            \
    X(GEOSisEmpty_r)                          \
    X(GEOSisValid_r)

#if LAM_LAZY
LAM_GEOS_FUNCS(LAM_LAZYLIB_EXTERN)

#define GEOSArea_r lam_dl_GEOSArea_r
#define GEOSBufferWithStyle_r lam_dl_GEOSBufferWithStyle_r
#define GEOSClipByRect_r lam_dl_GEOSClipByRect_r
#define GEOSConstrainedDelaunayTriangulation_r lam_dl_GEOSConstrainedDelaunayTriangulation_r
#define GEOSContext_setErrorMessageHandler_r lam_dl_GEOSContext_setErrorMessageHandler_r
#define GEOSCoordSeq_create_r lam_dl_GEOSCoordSeq_create_r
#define GEOSCoveredBy_r lam_dl_GEOSCoveredBy_r
#define GEOSCoordSeq_getSize_r lam_dl_GEOSCoordSeq_getSize_r
#define GEOSCoordSeq_getXY_r lam_dl_GEOSCoordSeq_getXY_r
#define GEOSCoordSeq_setXY_r lam_dl_GEOSCoordSeq_setXY_r
#define GEOSDifference_r lam_dl_GEOSDifference_r
#define GEOSDifferencePrec_r lam_dl_GEOSDifferencePrec_r
#define GEOSGeomGetX_r lam_dl_GEOSGeomGetX_r
#define GEOSGeomGetY_r lam_dl_GEOSGeomGetY_r
#define GEOSGeomTypeId_r lam_dl_GEOSGeomTypeId_r
#define GEOSGeom_clone_r lam_dl_GEOSGeom_clone_r
#define GEOSGeom_createCollection_r lam_dl_GEOSGeom_createCollection_r
#define GEOSGeom_createLineString_r lam_dl_GEOSGeom_createLineString_r
#define GEOSGeom_createLinearRing_r lam_dl_GEOSGeom_createLinearRing_r
#define GEOSGeom_createPolygon_r lam_dl_GEOSGeom_createPolygon_r
#define GEOSGeom_destroy_r lam_dl_GEOSGeom_destroy_r
#define GEOSGeom_getCoordSeq_r lam_dl_GEOSGeom_getCoordSeq_r
#define GEOSGeom_getXMax_r lam_dl_GEOSGeom_getXMax_r
#define GEOSGeom_getXMin_r lam_dl_GEOSGeom_getXMin_r
#define GEOSGeom_getYMax_r lam_dl_GEOSGeom_getYMax_r
#define GEOSGeom_getYMin_r lam_dl_GEOSGeom_getYMin_r
#define GEOSGetExteriorRing_r lam_dl_GEOSGetExteriorRing_r
#define GEOSGetGeometryN_r lam_dl_GEOSGetGeometryN_r
#define GEOSGetInteriorRingN_r lam_dl_GEOSGetInteriorRingN_r
#define GEOSGetNumGeometries_r lam_dl_GEOSGetNumGeometries_r
#define GEOSGetNumInteriorRings_r lam_dl_GEOSGetNumInteriorRings_r
#define GEOSIntersection_r lam_dl_GEOSIntersection_r
#define GEOSIntersectionPrec_r lam_dl_GEOSIntersectionPrec_r
#define GEOSMakeValidParams_create_r lam_dl_GEOSMakeValidParams_create_r
#define GEOSMakeValidParams_destroy_r lam_dl_GEOSMakeValidParams_destroy_r
#define GEOSMakeValidParams_setKeepCollapsed_r lam_dl_GEOSMakeValidParams_setKeepCollapsed_r
#define GEOSMakeValidParams_setMethod_r lam_dl_GEOSMakeValidParams_setMethod_r
#define GEOSMakeValidWithParams_r lam_dl_GEOSMakeValidWithParams_r
#define GEOSPointOnSurface_r lam_dl_GEOSPointOnSurface_r
#define GEOSPolygonize_r lam_dl_GEOSPolygonize_r
#define GEOSUnaryUnion_r lam_dl_GEOSUnaryUnion_r
#define GEOSUnaryUnionPrec_r lam_dl_GEOSUnaryUnionPrec_r
#define GEOSUnionPrec_r lam_dl_GEOSUnionPrec_r
#define GEOS_finish_r lam_dl_GEOS_finish_r
#define GEOS_init_r lam_dl_GEOS_init_r
#define GEOSisEmpty_r lam_dl_GEOSisEmpty_r
#define GEOSisValid_r lam_dl_GEOSisValid_r
#endif

#endif

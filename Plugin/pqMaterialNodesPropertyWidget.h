// placeholder (being written)
#ifndef pqMaterialNodesPropertyWidget_h
#define pqMaterialNodesPropertyWidget_h
#include "pqPropertyWidget.h"
class pqMaterialNodesPropertyWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;
public:
  pqMaterialNodesPropertyWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqMaterialNodesPropertyWidget() override;
};
#endif
